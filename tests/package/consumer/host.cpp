// The package test's host (tests/package/package_test.cmake): an engine-style program built
// against the installed package only. It opens its own EGL context and framebuffer, draws its
// own depth pass, and lets shadowcert's host layer (gpu/host_shadow_volumes.h) count and light
// the shadow of a triangle over a floor, for a method that needs pipeline/ (smooth-gpu) and
// for cs reading the host's own vertex buffer; each frame must equal shadowcert's offscreen
// render pixel for pixel. Exit 0 when all checks pass, 1 when one fails; without any EGL
// device it says so and exits 0, unless SHADOWCERT_REQUIRE_GL=1 (then 1).
#include <array>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include <glm/gtc/type_ptr.hpp>

#include "gpu/camera_transform.h"
#include "gpu/egl_context.h"
#include "gpu/gl_environment_error.h"
#include "gpu/host_shadow_volumes.h"
#include "gpu/offscreen_target.h"
#include "gpu/shader_compiler.h"
#include "gpu/shadow_method_renderer.h"
#include "pipeline/drawn_method_scene.h"

namespace {

using namespace shadowcert;

// The host's depth pass: the position expression the state contract asks for.
constexpr const char* kVertex = R"(#version 450 core
layout(location = 0) in vec4 position;
layout(location = 2) in vec3 albedo;
layout(location = 0) uniform mat4 world_to_clip;
invariant gl_Position;
layout(location = 0) out vec3 surface_albedo;
void main() { precise vec4 clip = world_to_clip * position; gl_Position = clip; surface_albedo = albedo; }
)";
constexpr const char* kFragment = R"(#version 450 core
layout(location = 0) in vec3 surface_albedo;
layout(location = 1) uniform vec4 colour;
layout(location = 0) out vec4 fragment;
void main() { fragment = vec4(surface_albedo * colour.rgb, 1.0); }
)";

Scene triangle_over_floor() {
  Scene scene;
  SceneMesh floor;
  floor.soup.vertices = {{-4, -4, 0}, {4, -4, 0}, {4, 4, 0}, {-4, 4, 0}};
  floor.soup.triangles = {{0, 1, 2}, {0, 2, 3}};
  SceneMesh caster;
  caster.soup.vertices = {{-1, -1, 1}, {1, -1, 1}, {0, 1, 1}};
  caster.soup.triangles = {{0, 1, 2}};
  scene.meshes = {floor, caster};
  scene.lights = {Light{{0.3, 0.2, 4.0, 1.0}}};
  scene.camera.eye = {0.0, -6.0, 5.0};
  scene.camera.target = {0.0, 0.0, 0.0};
  scene.camera.width = 96;
  scene.camera.height = 72;
  return scene;
}

int run() {
  int failures = 0;
  const gpu::EglContext context = gpu::open_gl_context("host", std::nullopt);
  const Scene scene = triangle_over_floor();
  for (const gpu::ShadowMethod method : {gpu::ShadowMethod::cs, gpu::ShadowMethod::smooth_gpu, gpu::ShadowMethod::cpu}) {
    const auto d = prepare_drawn_method_scene(scene, method, StencilChoice::automatic);
    const Camera& camera = d->scene.camera;
    // shadowcert's own frame.
    const gpu::OffscreenTarget offscreen(camera.width, camera.height);
    gpu::ShadowMethodRenderer renderer(method, d->method_scene(), d->renderer_options());
    const gpu::RgbaImage expected = renderer.render(offscreen, camera).colour;

    // The host's: its framebuffer (an OffscreenTarget is one FBO), receivers, program, camera.
    const gpu::OffscreenTarget target(camera.width, camera.height);
    const gpu::ShadedSoupMesh receivers(d->parts);
    const gpu::Shader vs = gpu::compile_shader(GL_VERTEX_SHADER, kVertex, "host.vert");
    const gpu::Shader fs = gpu::compile_shader(GL_FRAGMENT_SHADER, kFragment, "host.frag");
    const gpu::Program program = gpu::link_program({&vs, &fs}, "host");
    const glm::mat4 clip(gpu::projection_matrix(camera) * gpu::view_matrix(camera));
    target.bind();
    target.clear({0.0f, 0.0f, 0.0f, 0.0f});
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glUseProgram(program.name());
    glProgramUniformMatrix4fv(program.name(), 0, 1, GL_FALSE, glm::value_ptr(clip));
    glProgramUniform4f(program.name(), 1, 0.15f, 0.15f, 0.15f, 1.0f);
    glBindVertexArray(receivers.vertex_array());
    glDrawArrays(GL_TRIANGLES, 0, receivers.vertex_count());
    glBindVertexArray(0);
    glUseProgram(0);

    gpu::HostShadowVolumes shadows(method, d->method_scene(), d->host_options());
    std::vector<float> host_vertices;  // the casters as the host keeps them: x, y, z floats
    for (const Vec3& p : d->casters.vertices)
      host_vertices.insert(host_vertices.end(), {float(p[0]), float(p[1]), float(p[2])});
    gpu::Buffer buffer = gpu::Buffer::create();
    glNamedBufferStorage(buffer.name(), static_cast<GLsizeiptr>(host_vertices.size() * sizeof(float)),
                         host_vertices.data(), 0);
    if (gpu::builds_volume_on_gpu(method))
      shadows.read_vertices_from({buffer.name(), 0, 0, GL_FLOAT, 3}, d->inputs.canonical.canonical_id);
    shadows.build();
    const gpu::HostReceivers r = gpu::host_receivers(receivers);
    shadows.draw_lit(clip, 0, r, {0.85f, 0.85f, 0.85f});
    const gpu::RgbaImage colour = target.read_colour();
    const bool equal = colour.pixels == expected.pixels;
    std::printf("%s: host frame of %s equals shadowcert's render pixel for pixel\n", equal ? "ok" : "FAILED",
                std::string(gpu::shadow_method_name(method)).c_str());
    failures += equal ? 0 : 1;
  }
  std::printf("%s\n", failures == 0 ? "host: all checks passed" : "host: some checks FAILED");
  return failures == 0 ? 0 : 1;
}

}  // namespace

int main() {
  try {
    return run();
  } catch (const gpu::NoGlDeviceError& e) {
    const char* required = std::getenv("SHADOWCERT_REQUIRE_GL");
    const bool must = required != nullptr && std::strcmp(required, "1") == 0;
    std::printf("host: no EGL device (%s)%s\n", e.what(), must ? ", but SHADOWCERT_REQUIRE_GL=1" : ": skipped");
    return must ? 1 : 0;
  } catch (const std::exception& e) {
    std::printf("host: FAILED: %s\n", e.what());
    return 1;
  }
}
