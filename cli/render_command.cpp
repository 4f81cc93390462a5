#include "cli/render_command.h"

#include <epoxy/gl.h>
#include <fmt/core.h>

#include <array>
#include <chrono>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cli/exit_code.h"
#include "cli/output_file.h"
#include "cli/scene_input.h"
#include "cli/volume_capture.h"
#include "core/input_error.h"
#include "exact/edge_multiplicity.h"
#include "scene/edge_table.h"
#include "exact/shadow_volume_chain.h"
#include "gpu/compute_volume.h"
#include "gpu/egl_context.h"
#include "gpu/geometry_shader_volume.h"
#include "gpu/tessellation_volume.h"
#include "gpu/gl_environment_error.h"
#include "gpu/offscreen_target.h"
#include "gpu/per_triangle_volume.h"
#include "gpu/png_image.h"
#include "gpu/shadow_map_renderer.h"
#include "gpu/shadow_volume_geometry.h"
#include "gpu/stencil_shadow_renderer.h"
#include "scene/canonical_soup.h"

namespace shadowcert::cli {
namespace {

// Frames drawn (without readback, each ended by glFinish) for the ms-per-frame figure: one
// frame alone would mostly time llvmpipe's first-use shader compilation.
constexpr int kTimedFrames = 5;

// Mesh colours, in scene order (cycled): only a picture, nothing is decided from them.
constexpr std::array<std::array<float, 3>, 4> kPalette{
    {{0.85f, 0.85f, 0.85f}, {0.95f, 0.55f, 0.35f}, {0.45f, 0.75f, 0.95f}, {0.6f, 0.9f, 0.5f}}};

struct RenderOptions {
  std::string input;
  std::string method = "cpu";
  bool zpass = false;
  bool zfail = false;
  std::string size;  // "WxH"; empty: the scene camera's
  std::string out;
  std::string counts;
  std::string mask;
  std::string json_file;
  std::string capture;  // the first light's volume as drawn (.vol, exact/captured_volume.h)
  std::optional<int> device;
  // --method shadowmap only (gpu/shadow_map_renderer.h). The size is wide so that a value
  // over the limit gets run_shadowmap's message rather than a parse error.
  long long shadowmap_size = gpu::kDefaultShadowMapSize;
  float shadowmap_bias = gpu::kDefaultShadowMapBias;
  float shadowmap_slope = gpu::kDefaultShadowMapSlope;
};

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

void apply_size(const std::string& size, Camera& camera) {
  if (size.empty()) return;
  const auto x = size.find('x');
  unsigned long w = 0, h = 0;
  try {
    if (x == std::string::npos) throw std::invalid_argument("no x");
    std::size_t used_w = 0, used_h = 0;
    w = std::stoul(size.substr(0, x), &used_w);
    h = std::stoul(size.substr(x + 1), &used_h);
    if (used_w != x || used_h != size.size() - x - 1) throw std::invalid_argument("trailing");
  } catch (const std::exception&) {
    throw CLI::ValidationError("--size", "expects WxH, e.g. 1024x768");
  }
  constexpr unsigned long kMaxSide = 16384;  // GL_MAX_RENDERBUFFER_SIZE of every driver we target
  if (w == 0 || h == 0 || w > kMaxSide || h > kMaxSide)
    throw CLI::ValidationError("--size", "each side must be in [1, 16384]");
  camera.width = static_cast<std::uint32_t>(w);
  camera.height = static_cast<std::uint32_t>(h);
}

// exact/'s symbolic chain to homogeneous floats (exact/shadow_volume_chain.h): ids [0, n) are
// the canonical vertices (w = 1); a point light's n + i is x_i's far vertex (x_i - l, 0), a
// directional light's n is (-l, 0). x - l is formed in double and rounded once. Quads
// (a, b, c, d) become (a, b, c) and (a, c, d), keeping the outward orientation.
gpu::ShadowVolumeGeometry to_geometry(const ShadowVolumeChain& chain, const Soup& canonical, const Light& light) {
  gpu::ShadowVolumeGeometry g;
  const auto& l = light.position;
  g.vertices.reserve(canonical.vertices.size() * 2);
  for (const Vec3& x : canonical.vertices)
    g.vertices.push_back({static_cast<float>(x[0]), static_cast<float>(x[1]), static_cast<float>(x[2]), 1.0f});
  if (chain.directional) {
    g.vertices.push_back({static_cast<float>(-l[0]), static_cast<float>(-l[1]), static_cast<float>(-l[2]), 0.0f});
  } else {
    for (const Vec3& x : canonical.vertices)
      g.vertices.push_back({static_cast<float>(x[0] - l[0]), static_cast<float>(x[1] - l[1]),
                            static_cast<float>(x[2] - l[2]), 0.0f});
  }
  g.triangles.reserve(chain.triangles.size() + 2 * chain.quads.size());
  for (const auto& t : chain.triangles) g.triangles.push_back(t);
  for (const auto& q : chain.quads) {
    g.triangles.push_back({q[0], q[1], q[2]});
    g.triangles.push_back({q[0], q[2], q[3]});
  }
  return g;
}

std::uint64_t count_pixels(const gpu::RgbaImage& colour, const gpu::GrayImage& stencil, bool lit) {
  std::uint64_t n = 0;
  for (std::size_t i = 0; i < stencil.pixels.size(); ++i) {
    const bool covered = colour.pixels[4 * i + 3] != 0;  // alpha 255 where a receiver was drawn
    if (covered && (stencil.pixels[i] == 0) == lit) ++n;
  }
  return n;
}

// --method shadowmap: no volume, one depth map per light (gpu/shadow_map_renderer.h). The
// outputs keep the stencil methods' shape; the counts image holds 0 where the first light's
// map comparison says lit and 1 where it says shadowed (a map has no counts).
int run_shadowmap(const RenderOptions& options) {
  const auto start = Clock::now();
  if (options.shadowmap_size < 1 || options.shadowmap_size > gpu::kMaxShadowMapSize)
    throw CLI::ValidationError("--shadowmap-size", fmt::format("must be in [1, {}] (a {}^2 depth texture), got {}",
                                                               gpu::kMaxShadowMapSize, gpu::kMaxShadowMapSize,
                                                               options.shadowmap_size));
  if (options.zpass) throw CLI::ValidationError("--zpass", "is a stencil option; shadowmap counts no volume");
  if (!options.capture.empty()) throw CLI::ValidationError("--capture", "shadowmap draws no volume to capture");
  Scene scene = load_scene_or_mesh(options.input);
  if (scene.lights.empty()) throw InputError(options.input, "the scene has no light");
  apply_size(options.size, scene.camera);
  const Soup merged = merged_soup(scene);
  if (merged.triangles.empty()) throw InputError(options.input, "no triangle to render");

  std::optional<gpu::EglContext> context;
  try {
    context.emplace(gpu::EglContextOptions{options.device, gpu::kGlDebugByDefault});
  } catch (const gpu::GlEnvironmentError& e) {
    throw gpu::GlEnvironmentError(
        "render needs OpenGL 4.5 core through headless EGL (a GPU driver or Mesa's llvmpipe: packages "
        "libegl-mesa0 libgl1-mesa-dri); " + std::string(e.what()));
  }
  auto stage = Clock::now();
  std::vector<gpu::ShadedSoupPart> parts;
  for (std::size_t i = 0; i < scene.meshes.size(); ++i)
    parts.push_back({&scene.meshes[i].soup, kPalette[i % kPalette.size()]});
  const gpu::ShadedSoupMesh receivers(parts);
  const gpu::OffscreenTarget target(scene.camera.width, scene.camera.height);
  const gpu::ShadowMapRenderer renderer(static_cast<std::uint32_t>(options.shadowmap_size));
  const gpu::SceneBounds bounds = gpu::soup_bounds(merged);
  gpu::ShadowMapOptions render_options;
  render_options.depth_bias = options.shadowmap_bias;
  render_options.slope_scale = options.shadowmap_slope;
  for (auto& c : render_options.light_colour) c /= static_cast<float>(scene.lights.size());
  const double upload_seconds = seconds_since(stage);

  stage = Clock::now();
  const gpu::StencilShadowFrame frame = renderer.render(target, receivers, bounds, scene.camera, scene.lights, render_options);
  const double first_frame_seconds = seconds_since(stage);
  render_options.read_back = false;
  stage = Clock::now();
  for (int i = 0; i < kTimedFrames; ++i) {
    (void)renderer.render(target, receivers, bounds, scene.camera, scene.lights, render_options);
    glFinish();
  }
  const double frame_ms = 1000.0 * seconds_since(stage) / kTimedFrames;

  for (const std::string& file : {options.out, options.counts, options.mask}) create_parent_directories(file);
  if (!options.out.empty()) gpu::write_png(options.out, frame.colour);
  if (!options.counts.empty()) gpu::write_png(options.counts, frame.first_stencil);
  if (!options.mask.empty()) gpu::write_png(options.mask, frame.first_lit_mask);
  const std::uint64_t lit = count_pixels(frame.colour, frame.first_stencil, true);
  const std::uint64_t shadowed = count_pixels(frame.colour, frame.first_stencil, false);
  const double seconds = seconds_since(start);

  fmt::print("{}: {} triangles, {} lights, {}x{}, shadowmap {}^2 (bias {}, slope {}) on {}\n", options.input,
             merged.triangles.size(), scene.lights.size(), scene.camera.width, scene.camera.height,
             options.shadowmap_size, options.shadowmap_bias, options.shadowmap_slope, context->renderer());
  fmt::print("  first light: {} lit, {} shadowed receiver pixels\n", lit, shadowed);
  fmt::print("  seconds: upload {:.3f}, first frame {:.3f}; {:.2f} ms per frame ({} frames)\n", upload_seconds,
             first_frame_seconds, frame_ms, kTimedFrames);
  if (!options.json_file.empty()) {
    write_json_file(options.json_file,
                    {{"input", options.input},
                     {"method", options.method},
                     {"shadowmap", {{"size", options.shadowmap_size},
                                    {"bias", options.shadowmap_bias},
                                    {"slope", options.shadowmap_slope}}},
                     {"size", {scene.camera.width, scene.camera.height}},
                     {"renderer", context->renderer()},
                     {"device", context->device()},
                     {"lights", scene.lights.size()},
                     {"lit_pixels", lit},
                     {"shadowed_pixels", shadowed},
                     {"frame_ms", frame_ms},
                     {"seconds", seconds},
                     {"stage_seconds", {{"upload", upload_seconds}, {"first_frame", first_frame_seconds}}}});
  }
  return kExitOk;
}

int run_render(const RenderOptions& options) {
  if (options.method == "shadowmap") return run_shadowmap(options);
  const auto start = Clock::now();
  const bool pertri = options.method == "pertri";
  const bool gs = options.method == "gs";
  const bool ts = options.method == "ts";
  const bool built_on_gpu = options.method == "cs" || pertri || gs || ts;  // all but cpu build their volumes on the GPU
  if (options.method != "cpu" && !built_on_gpu)
    throw CLI::ValidationError("--method", "only 'cpu', 'cs', 'pertri', 'gs', 'ts' and 'shadowmap' exist");
  if (options.zpass && options.zfail) throw CLI::ValidationError("--zpass", "excludes --zfail");
  Scene scene = load_scene_or_mesh(options.input);
  if (scene.lights.empty()) throw InputError(options.input, "the scene has no light");
  apply_size(options.size, scene.camera);
  const Soup merged = merged_soup(scene);
  if (merged.triangles.empty()) throw InputError(options.input, "no triangle to render");

  // The volumes: one exact chain per light (DESIGN.md §3); cs builds its own on the GPU from
  // the same canonical soup and edge table (gpu/compute_volume.h).
  auto stage = Clock::now();
  const CanonicalSoup canonical = canonical_soup(merged);
  const EdgeTable table = build_edge_table(canonical.soup);
  std::vector<gpu::ShadowVolumeGeometry> geometries;
  for (const Light& light : built_on_gpu ? std::vector<Light>{} : scene.lights) {
    const EdgeMultiplicities m = exact_multiplicities(canonical.soup, table, light);
    geometries.push_back(to_geometry(assemble_chain(canonical.soup, table, m, light), canonical.soup, light));
  }
  const double chain_seconds = seconds_since(stage);

  std::optional<gpu::EglContext> context;
  try {
    context.emplace(gpu::EglContextOptions{options.device, gpu::kGlDebugByDefault});
  } catch (const gpu::GlEnvironmentError& e) {
    // Rethrown with what the user needs to know; main maps it to exit code 2.
    throw gpu::GlEnvironmentError(
        "render needs OpenGL 4.5 core through headless EGL (a GPU driver or Mesa's llvmpipe: packages "
        "libegl-mesa0 libgl1-mesa-dri); " + std::string(e.what()));
  }

  stage = Clock::now();
  std::vector<gpu::ShadedSoupPart> parts;
  for (std::size_t i = 0; i < scene.meshes.size(); ++i)
    parts.push_back({&scene.meshes[i].soup, kPalette[i % kPalette.size()]});
  const gpu::ShadedSoupMesh receivers(parts);
  std::vector<std::unique_ptr<gpu::ShadowVolumeMesh>> volumes;
  std::optional<gpu::ComputeVolumeSoup> cs_soup;
  std::vector<std::unique_ptr<gpu::ComputeShadowVolume>> cs_volumes;
  std::vector<std::unique_ptr<gpu::PerTriangleShadowVolume>> pertri_volumes;  // Milet 2014 §2.1
  std::vector<std::unique_ptr<gpu::GeometryShaderShadowVolume>> gs_volumes;
  std::vector<std::unique_ptr<gpu::TessellationShadowVolume>> ts_volumes;
  std::vector<gpu::LightVolume> lights;
  if (built_on_gpu) cs_soup.emplace(canonical.soup, table);
  for (std::size_t i = 0; i < scene.lights.size(); ++i) {
    if (pertri) {
      pertri_volumes.push_back(std::make_unique<gpu::PerTriangleShadowVolume>(*cs_soup));
      lights.push_back({scene.lights[i], nullptr, pertri_volumes.back()->draw()});
    } else if (gs) {
      gs_volumes.push_back(std::make_unique<gpu::GeometryShaderShadowVolume>(*cs_soup, table));
      lights.push_back({scene.lights[i], nullptr, gs_volumes.back()->draw()});
    } else if (ts) {
      ts_volumes.push_back(std::make_unique<gpu::TessellationShadowVolume>(*cs_soup, table));
      lights.push_back({scene.lights[i], nullptr, ts_volumes.back()->draw()});
    } else if (built_on_gpu) {
      cs_volumes.push_back(std::make_unique<gpu::ComputeShadowVolume>(*cs_soup));
      lights.push_back({scene.lights[i], nullptr, cs_volumes.back()->draw()});
    } else {
      volumes.push_back(std::make_unique<gpu::ShadowVolumeMesh>(geometries[i]));
      lights.push_back({scene.lights[i], volumes.back().get()});
    }
  }
  // cs rebuilds its volumes in every frame (a moving light costs nothing more), so its frame
  // time includes the compute passes; cpu's chains are built once, before the frames.
  const auto build_cs_volumes = [&] {
    for (std::size_t i = 0; i < cs_volumes.size(); ++i) cs_volumes[i]->build(scene.lights[i]);
    for (std::size_t i = 0; i < pertri_volumes.size(); ++i) pertri_volumes[i]->build(scene.lights[i]);
    for (std::size_t i = 0; i < gs_volumes.size(); ++i) gs_volumes[i]->build(scene.lights[i]);
    for (std::size_t i = 0; i < ts_volumes.size(); ++i) ts_volumes[i]->build(scene.lights[i]);
  };
  const gpu::OffscreenTarget target(scene.camera.width, scene.camera.height);
  const gpu::StencilShadowRenderer renderer;
  gpu::StencilShadowOptions render_options;
  render_options.method = options.zpass ? gpu::StencilMethod::zpass : gpu::StencilMethod::zfail;
  for (auto& c : render_options.light_colour) c /= static_cast<float>(scene.lights.size());
  const double upload_seconds = seconds_since(stage);

  stage = Clock::now();
  build_cs_volumes();
  std::uint64_t volume_triangles = built_on_gpu ? 0 : geometries.front().triangles.size();
  if (built_on_gpu) {
    // The output is sized for the worst case but clamped to one storage block: say so
    // rather than draw a partial (open) volume.
    const auto check_capacity = [&](const auto& gpu_volumes) {
      for (const auto& v : gpu_volumes)
        if (v->read_requested_vertices() > v->capacity_vertices())
          throw InputError(options.input, "the " + options.method + " volume needs more vertices than its GL " +
                                              "storage buffers hold (" + std::to_string(v->capacity_vertices()) + ")");
    };
    check_capacity(cs_volumes);
    check_capacity(pertri_volumes);
    check_capacity(gs_volumes);
    check_capacity(ts_volumes);
    volume_triangles = (pertri ? pertri_volumes.front()->read_requested_vertices()
                        : gs   ? gs_volumes.front()->read_requested_vertices()
                        : ts   ? ts_volumes.front()->read_requested_vertices()
                               : cs_volumes.front()->read_requested_vertices()) / 3;
  }
  const gpu::StencilShadowFrame frame = renderer.render(target, receivers, scene.camera, lights, render_options);
  const double first_frame_seconds = seconds_since(stage);
  render_options.read_back = false;
  stage = Clock::now();
  for (int i = 0; i < kTimedFrames; ++i) {
    build_cs_volumes();
    (void)renderer.render(target, receivers, scene.camera, lights, render_options);
    glFinish();
  }
  const double frame_ms = 1000.0 * seconds_since(stage) / kTimedFrames;

  for (const std::string& file : {options.out, options.counts, options.mask}) create_parent_directories(file);
  if (!options.out.empty()) gpu::write_png(options.out, frame.colour);
  if (!options.counts.empty()) gpu::write_png(options.counts, frame.first_stencil);
  if (!options.mask.empty()) gpu::write_png(options.mask, frame.first_lit_mask);
  if (!options.capture.empty())  // what was drawn, so that certify --volume checks the GPU's own output
    write_capture(options.capture,
                  built_on_gpu ? captured_volume(pertri ? pertri_volumes.front()->read_triangles()
                                              : gs  ? gs_volumes.front()->read_triangles()
                                              : ts  ? ts_volumes.front()->read_triangles()
                                              : cs_volumes.front()->read_triangles()) : captured_volume(geometries.front()),
                  options.input + ", method " + options.method + ", first light");
  const std::uint64_t lit = count_pixels(frame.colour, frame.first_stencil, true);
  const std::uint64_t shadowed = count_pixels(frame.colour, frame.first_stencil, false);
  const double seconds = seconds_since(start);

  const char* method = options.zpass ? "zpass" : "zfail";
  fmt::print("{}: {} triangles, {} lights, {}x{}, {}/{} on {}\n", options.input, merged.triangles.size(),
             scene.lights.size(), scene.camera.width, scene.camera.height, options.method, method,
             context->renderer());
  fmt::print("  volume triangles (first light) {}\n", volume_triangles);
  fmt::print("  first light: {} lit, {} shadowed receiver pixels\n", lit, shadowed);
  fmt::print("  seconds: chains {:.3f}, upload {:.3f}, first frame {:.3f}; {:.2f} ms per frame ({} frames)\n",
             chain_seconds, upload_seconds, first_frame_seconds, frame_ms, kTimedFrames);
  if (!options.json_file.empty()) {
    write_json_file(options.json_file,
                    {{"input", options.input},
                     {"method", options.method},
                     {"stencil", method},
                     {"size", {scene.camera.width, scene.camera.height}},
                     {"renderer", context->renderer()},
                     {"device", context->device()},
                     {"lights", scene.lights.size()},
                     {"lit_pixels", lit},
                     {"shadowed_pixels", shadowed},
                     {"frame_ms", frame_ms},
                     {"seconds", seconds},
                     {"stage_seconds",
                      {{"chains", chain_seconds}, {"upload", upload_seconds}, {"first_frame", first_frame_seconds}}}});
  }
  return kExitOk;
}

}  // namespace

void add_render_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<RenderOptions>();
  CLI::App* cmd = app.add_subcommand(
      "render",
      "Stencil shadow volumes with OpenGL 4.5 core (headless EGL; DESIGN.md 3, 5). Lights are drawn one after "
      "another; --counts, --mask and the pixel counts are for the FIRST light");
  cmd->add_option("input", options->input, "Mesh file (.obj .off .ply .stl) or scene (.json)")->required();
  cmd->add_option("--method", options->method,
                  "How the volume is built: cpu (the exact chain from exact/, drawn as is), cs (compute "
                  "shader, float reference-edge multiplicities, rebuilt every frame; gpu/compute_volume.h), "
                  "pertri (compute shader, every triangle's closed volume, no silhouette, rebuilt every frame; "
                  "gpu/per_triangle_volume.h), gs (geometry shader over edge records, float reference-edge "
                  "multiplicities, captured by transform feedback, rebuilt every frame; "
                  "gpu/geometry_shader_volume.h) or ts (tessellation over edge-record patches, the same "
                  "multiplicities and capture; gpu/tessellation_volume.h). shadowmap (no volume: a depth map from each light, --shadowmap-size/-bias/-slope; gpu/shadow_map_renderer.h)")
      ->capture_default_str();
  cmd->add_flag("--zfail", options->zfail, "Count faces behind the visible point (default; right with the eye in a volume)");
  cmd->add_flag("--zpass", options->zpass, "Count faces in front of the visible point (wrong with the eye in a volume)");
  cmd->add_option("--size", options->size, "Image size WxH (default: the scene camera's)");
  cmd->add_option("--out", options->out, "Write the shaded image (RGBA PNG; alpha 0 where no surface)");
  cmd->add_option("--counts", options->counts, "Write the first light's stencil counts mod 256 (8-bit gray PNG)");
  cmd->add_option("--mask", options->mask, "Write the first light's lit mask (255 where the count is 0)");
  cmd->add_option("--json", options->json_file, "Write method, size, renderer, pixel counts and timings as JSON");
  cmd->add_option("--capture", options->capture,
                  "Write the first light's volume as drawn (.vol text; check it with certify --volume FILE)");
  cmd->add_option("--shadowmap-size", options->shadowmap_size,
                  "shadowmap: side of the square depth map in texels, at most 16384")
      ->capture_default_str();
  cmd->add_option("--shadowmap-bias", options->shadowmap_bias,
                  "shadowmap: constant bias subtracted from the light-space depth (window units, [0, 1]) "
                  "before the comparison; larger trades acne for detached shadows")
      ->capture_default_str();
  cmd->add_option("--shadowmap-slope", options->shadowmap_slope,
                  "shadowmap: glPolygonOffset slope factor of the depth pass (for surfaces edge-on to the light)")
      ->capture_default_str();
  cmd->add_option("--device", options->device, "Use EGL device N (default: a hardware device, else llvmpipe)");
  cmd->callback([options, &exit_code] { exit_code = run_render(*options); });
}

}  // namespace shadowcert::cli
