// An engine-style host of shadowcert's GL layer (docs/engine-integration.md#the-example-walked-through):
// its own GLFW window and GL 4.5 context, its own vertex buffer (a floor and a box, interleaved
// position, normal, colour), its own shaders and lighting, its own camera with a finite far
// plane. shadowcert only counts the box's shadow volume into the window's stencil buffer
// (the stencil-only entry), built on the GPU from the host's own vertex buffer; the host then
// lights where the count is 0. The light circles the box.
//
//   shadow_host                    a window until Esc or close
//   shadow_host --frames N         N frames, then exit
//   shadow_host --frames N --check after frame N, exit 1 unless the floor is dark at the box's
//                                  shadow's centre and lit at its mirror image
#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "gpu/host_shadow_volumes.h"
#include "gpu/shader_compiler.h"
#include "gpu/shadow_method_renderer.h"  // ShadowMethodScene
#include "scene/canonical_soup.h"
#include "scene/edge_table.h"

namespace {

// ---- the host's own scene: a 10 x 10 floor at y = 0 and a unit box at height 1 to 2 --------
struct Vertex {
  float position[3], normal[3], colour[3];
};

void add_quad(std::vector<Vertex>& v, std::vector<unsigned>& idx, glm::vec3 o, glm::vec3 u, glm::vec3 w,
              glm::vec3 colour) {
  const glm::vec3 n = glm::normalize(glm::cross(u, w));
  const auto first = static_cast<unsigned>(v.size());
  for (const glm::vec3 p : {o, o + u, o + u + w, o + w})
    v.push_back({{p.x, p.y, p.z}, {n.x, n.y, n.z}, {colour.x, colour.y, colour.z}});
  idx.insert(idx.end(), {first, first + 1, first + 2, first, first + 2, first + 3});
}

constexpr const char* kVertexShader = R"(#version 450 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec3 colour;
layout(location = 0) uniform mat4 world_to_clip;
// shadowcert's state contract: the depth the volumes are tested against comes from exactly
// this expression with the matrix they are drawn with (invariant, precise: no fused rounding).
invariant gl_Position;
out vec3 world_position, world_normal, albedo;
void main() {
  precise vec4 clip = world_to_clip * vec4(position, 1.0);
  gl_Position = clip;
  world_position = position;
  world_normal = normal;
  albedo = colour;
}
)";
constexpr const char* kFragmentShader = R"(#version 450 core
in vec3 world_position, world_normal, albedo;
layout(location = 1) uniform vec3 light;
layout(location = 2) uniform int lit;  // 0: ambient pass, 1: the light's pass
out vec4 fragment;
void main() {
  if (lit == 0) { fragment = vec4(0.2 * albedo, 1.0); return; }
  vec3 n = normalize(world_normal);
  fragment = vec4(0.8 * albedo * max(dot(n, normalize(light - world_position)), 0.0), 0.0);
}
)";

}  // namespace

int main(int argc, char** argv) {
  int frames = 0;
  bool check = false;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--frames") == 0 && i + 1 < argc) frames = std::atoi(argv[++i]);
    else if (std::strcmp(argv[i], "--check") == 0) check = true;
    else { std::fprintf(stderr, "usage: shadow_host [--frames N] [--check]\n"); return 2; }
  }
  if (!glfwInit()) { std::fprintf(stderr, "shadow_host: no display (GLFW could not start)\n"); return 2; }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_STENCIL_BITS, 8);  // shadowcert counts into the window's stencil
  const int width = 640, height = 480;
  GLFWwindow* window = glfwCreateWindow(width, height, "shadowcert: shadow_host", nullptr, nullptr);
  if (window == nullptr) { std::fprintf(stderr, "shadow_host: no GL 4.5 core window\n"); glfwTerminate(); return 2; }
  glfwMakeContextCurrent(window);
  int status = 0;
  try {
    using namespace shadowcert;
    // ---- the host's buffers: the floor's 4 vertices, then the box's 24 (4 per face)
    std::vector<Vertex> vertices;
    std::vector<unsigned> indices;
    add_quad(vertices, indices, {-5, 0, 5}, {10, 0, 0}, {0, 0, -10}, {0.8f, 0.8f, 0.8f});
    const unsigned box_first = static_cast<unsigned>(vertices.size());
    const glm::vec3 red{0.8f, 0.3f, 0.2f};
    const float a = -0.5f, b = 0.5f, lo = 1.0f, hi = 2.0f;
    add_quad(vertices, indices, {a, lo, b}, {1, 0, 0}, {0, 1, 0}, red);   // +z
    add_quad(vertices, indices, {b, lo, a}, {-1, 0, 0}, {0, 1, 0}, red);  // -z
    add_quad(vertices, indices, {b, lo, b}, {0, 0, -1}, {0, 1, 0}, red);  // +x
    add_quad(vertices, indices, {a, lo, a}, {0, 0, 1}, {0, 1, 0}, red);   // -x
    add_quad(vertices, indices, {a, hi, b}, {1, 0, 0}, {0, 0, -1}, red);  // top
    add_quad(vertices, indices, {a, lo, a}, {1, 0, 0}, {0, 0, 1}, red);   // bottom
    GLuint buffers[2], vao = 0, program = 0;
    glCreateBuffers(2, buffers);
    glNamedBufferStorage(buffers[0], static_cast<GLsizeiptr>(vertices.size() * sizeof(Vertex)), vertices.data(), 0);
    glNamedBufferStorage(buffers[1], static_cast<GLsizeiptr>(indices.size() * sizeof(unsigned)), indices.data(), 0);
    glCreateVertexArrays(1, &vao);
    glVertexArrayVertexBuffer(vao, 0, buffers[0], 0, sizeof(Vertex));
    glVertexArrayElementBuffer(vao, buffers[1]);
    for (GLuint attribute = 0; attribute < 3; ++attribute) {
      glVertexArrayAttribFormat(vao, attribute, 3, GL_FLOAT, GL_FALSE, attribute * 3 * sizeof(float));
      glVertexArrayAttribBinding(vao, attribute, 0);
      glEnableVertexArrayAttrib(vao, attribute);
    }
    const gpu::Shader vs = gpu::compile_shader(GL_VERTEX_SHADER, kVertexShader, "host.vert");
    const gpu::Shader fs = gpu::compile_shader(GL_FRAGMENT_SHADER, kFragmentShader, "host.frag");
    const gpu::Program host_program = gpu::link_program({&vs, &fs}, "host");
    program = host_program.name();

    // ---- shadowcert, once: the box as a soup (its topology), then the GL layer for cs
    Soup box;
    for (unsigned i = box_first; i < vertices.size(); ++i)
      box.vertices.push_back({vertices[i].position[0], vertices[i].position[1], vertices[i].position[2]});
    for (std::size_t i = 6; i < indices.size(); i += 3)  // the box's triangles, after the floor's two
      box.triangles.push_back({indices[i] - box_first, indices[i + 1] - box_first, indices[i + 2] - box_first});
    const CanonicalSoup canonical = canonical_soup(box);  // welds the faces' shared corners
    const EdgeTable table = build_edge_table(canonical.soup);
    const std::vector<Light> lights{Light{{3.0, 6.0, 0.0, 1.0}}};
    gpu::ShadowMethodScene casters;
    casters.lights = lights;
    casters.canonical = &canonical.soup;
    casters.table = &table;
    gpu::HostShadowVolumes shadows(gpu::ShadowMethod::cs, casters);
    // The box's positions are read from the host's own buffer at every build.
    shadows.read_vertices_from({buffers[0], static_cast<GLintptr>(box_first * sizeof(Vertex)), sizeof(Vertex), GL_FLOAT, 3},
                               canonical.canonical_id);

    // ---- the frames
    const glm::mat4 view = glm::lookAt(glm::vec3(0, 6, 9), glm::vec3(0, 0.5f, 0), glm::vec3(0, 1, 0));
    const glm::mat4 projection = glm::perspective(glm::radians(45.0f), float(width) / height, 0.1f, 100.0f);
    const glm::mat4 world_to_clip = projection * view;  // a finite far plane: shadowcert clamps depth
    glProgramUniformMatrix4fv(program, 0, 1, GL_FALSE, glm::value_ptr(world_to_clip));
    glm::vec3 light{3, 6, 0};
    for (int frame = 1; glfwWindowShouldClose(window) == GLFW_FALSE; ++frame) {
      const double t = 0.02 * frame;
      light = {3.0f * float(std::cos(t)), 6.0f, 3.0f * float(std::sin(t))};
      // 1. the host's depth pass, in ambient light
      glViewport(0, 0, width, height);
      glClearColor(0.05f, 0.05f, 0.1f, 1.0f);
      glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
      glEnable(GL_DEPTH_TEST);
      glDepthFunc(GL_LESS);
      glDepthMask(GL_TRUE);
      glUseProgram(program);
      glProgramUniform1i(program, 2, 0);
      glBindVertexArray(vao);
      glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(indices.size()), GL_UNSIGNED_INT, nullptr);
      // 2. shadowcert: the box's volume for this light, counted into the stencil
      shadows.set_light(0, Light{{light.x, light.y, light.z, 1.0}});
      shadows.build();
      shadows.draw_stencil(world_to_clip, 0);
      // 3. the host's light pass where the count is 0 (its own state: shadowcert restored ours)
      glEnable(GL_STENCIL_TEST);
      glStencilFunc(GL_EQUAL, 0, 0xFF);
      glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
      glDepthFunc(GL_EQUAL);
      glDepthMask(GL_FALSE);
      glEnable(GL_BLEND);
      glBlendFunc(GL_ONE, GL_ONE);
      glProgramUniform3f(program, 1, light.x, light.y, light.z);
      glProgramUniform1i(program, 2, 1);
      glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(indices.size()), GL_UNSIGNED_INT, nullptr);
      glDisable(GL_BLEND);
      glDisable(GL_STENCIL_TEST);
      glDepthMask(GL_TRUE);
      if (frames != 0 && frame == frames) {
        if (check) {  // the floor at the shadow's centre (light through the box's centre) and its mirror
          const glm::vec3 centre{0, 1.5f, 0};
          const glm::vec3 shadow = light + (centre - light) * (light.y / (light.y - centre.y));
          const glm::vec3 mirror{-shadow.x, 0, -shadow.z};
          unsigned char dark[4], bright[4];
          for (auto [p, out] : {std::pair{shadow, dark}, std::pair{mirror, bright}}) {
            const glm::vec3 s = glm::project(p, view, projection, glm::vec4(0, 0, width, height));
            glReadPixels(int(s.x), int(s.y), 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, out);
          }
          const bool ok = dark[0] < 60 && bright[0] > dark[0] + 60;
          std::printf("%s: floor red %d in the box's shadow, %d outside it\n", ok ? "ok" : "FAILED", dark[0], bright[0]);
          status = ok ? 0 : 1;
        }
        break;
      }
      glfwSwapBuffers(window);
      glfwPollEvents();
      if (glfwGetKey(window, GLFW_KEY_ESCAPE) == GLFW_PRESS) break;
    }
    glDeleteVertexArrays(1, &vao);
    glDeleteBuffers(2, buffers);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "shadow_host: %s\n", e.what());
    status = 1;
  }
  glfwDestroyWindow(window);
  glfwTerminate();
  return status;
}
