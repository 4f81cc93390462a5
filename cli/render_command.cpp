#include "cli/render_command.h"

#include <fmt/core.h>

#include <array>
#include <chrono>
#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>
#include <numeric>
#include <optional>
#include <string>
#include <vector>

#include "cli/exit_code.h"
#include "cli/frame_timing_output.h"
#include "cli/light_image_output.h"
#include "cli/option_values.h"
#include "cli/silhouette_output.h"
#include "cli/stencil_output.h"
#include "cli/wall_clock.h"
#include "pipeline/mesh_palette.h"
#include "io/output_file.h"
#include "io/scene_input.h"
#include "core/eye_frame.h"
#include "core/input_error.h"
#include "io/volume_file.h"
#include "gpu/egl_context.h"
#include "gpu/frame_timing.h"
#include "gpu/offscreen_target.h"
#include "gpu/png_image.h"
#include "gpu/shadow_method_renderer.h"
#include "pipeline/method_inputs.h"
#include "pipeline/method_registry.h"
#include "pipeline/ray_traced_comparison.h"
#include "pipeline/scene_smoothies.h"
#include "pipeline/stencil_choice.h"
#include "scene/merged_soup.h"

namespace shadowcert::cli {
namespace {


struct RenderOptions {
  std::string input;
  std::string method = "cpu";
  bool method_given = false;  // --method on the command line (--pcf and --pcss then must agree)
  std::string sign = "exact";  // --sign exact|float (gpu/sign_mode.h)
  unsigned threads = 0;        // --threads: the ray tracer's (rt, rt-robust); 0: every core
  std::string stencil;  // --stencil auto|zpass|zfail; empty: not given (the aliases, else zfail)
  bool zpass = false;
  bool zfail = false;
  std::string size;  // "WxH"; empty: the scene camera's
  std::string out;
  std::string counts;
  std::string mask;
  std::string json_file;
  std::string capture;  // the first light's volume as drawn (.vol, io/volume_file.h)
  std::optional<int> device;
  // --method shadowmap only (gpu/shadow_map_renderer.h). The size is wide so that a value
  // over the limit gets validate()'s message rather than a parse error.
  long long shadowmap_size = gpu::kDefaultShadowMapSize;
  float shadowmap_bias = gpu::kDefaultShadowMapBias;
  float shadowmap_slope = gpu::kDefaultShadowMapSlope;
  // The soft shadow-map methods (docs/smoothies.md): --pcf K and --pcss pick pcf and pcss (and
  // give their parameters), --light-radius is pcss's R, --smoothie-* the smoothies' geometry.
  std::optional<long long> pcf;
  bool pcss = false;
  std::optional<double> light_radius;
  std::optional<double> light_angle;  // pcss: a directional light's angular radius, degrees
  std::optional<double> smoothie_width;
  std::optional<std::string> smoothie_space;
  std::string light_image;  // --light-image FILE.png (and FILE.pfm, cli/light_image_output.h)
  bool timing = false;  // GPU stage times (gpu/gpu_stage_timer.h) over `frames` frames
  std::size_t frames = kDefaultTimingFrames;
  SilhouetteOptions silhouette;  // --epsilon, --crease-angle
};


struct ValidatedRenderOptions {
  gpu::ShadowMethod method;
  StencilChoice stencil;
};

// ---- step 1: the options, checked before any file is read -------------------------------------

// --pcf and --pcss name their method: alone they choose it, with --method they must agree.
gpu::ShadowMethod method_of(const RenderOptions& options) {
  gpu::ShadowMethod method = shadow_method_option(options.method, "--method");
  if (options.pcf && options.pcss) throw CLI::ValidationError("--pcf", "excludes --pcss (two filters)");
  const auto implied = [&](bool given, gpu::ShadowMethod implied_method, const char* option) {
    if (!given) return;
    if (options.method_given && method != implied_method)
      throw CLI::ValidationError(option, fmt::format("picks the {} method; it contradicts --method {}",
                                                     gpu::shadow_method_name(implied_method), options.method));
    method = implied_method;
  };
  implied(options.pcf.has_value(), gpu::ShadowMethod::pcf, "--pcf");
  implied(options.pcss, gpu::ShadowMethod::pcss, "--pcss");
  return method;
}

// The method and the stencil choice, after the checks that need no input file.
ValidatedRenderOptions validate(const RenderOptions& options) {
  const gpu::ShadowMethod method = method_of(options);
  const StencilChoice stencil = stencil_option(options.stencil, options.zpass, options.zfail);
  if (options.pcf && (*options.pcf < 1 || *options.pcf > gpu::kMaxPcfKernel || *options.pcf % 2 == 0))
    throw CLI::ValidationError("--pcf", fmt::format("K must be odd and in [1, {}] (K x K taps centred on the "
                                                    "point's texel), got {}",
                                                    gpu::kMaxPcfKernel, *options.pcf));
  // What the method reads is its registry entry's (pipeline/method_registry.h): an option of
  // another method is refused, naming the methods that read it.
  const MethodEntry& entry = method_entry(method);
  const auto refuse_unread = [&](MethodOption option, bool given, const std::string& flag) {
    if (given && !entry.reads(option))
      throw CLI::ValidationError(flag, fmt::format("is read by {} only; --method {} does not read it",
                                                   methods_reading(option), entry.name()));
  };
  refuse_unread(MethodOption::light_radius, options.light_radius.has_value(), "--light-radius");
  refuse_unread(MethodOption::light_radius, options.light_angle.has_value(), "--light-angle");
  refuse_unread(MethodOption::smoothie, options.smoothie_width.has_value(), "--smoothie-width");
  refuse_unread(MethodOption::smoothie, options.smoothie_space.has_value(), "--smoothie-space");
  refuse_unread(MethodOption::capture, !options.capture.empty(), "--capture");
  // z-fail is every volume's default: only another choice says a volume is to be counted.
  refuse_unread(MethodOption::stencil, stencil != StencilChoice::zfail, options.zpass ? "--zpass" : "--stencil");
  if (options.light_radius && (!std::isfinite(*options.light_radius) || !(*options.light_radius > 0.0)))
    throw CLI::ValidationError("--light-radius",
                               fmt::format("must be finite and > 0 (world units), got {}", *options.light_radius));
  if (options.light_angle) check_light_angle(*options.light_angle);
  if (options.smoothie_width && (!std::isfinite(*options.smoothie_width) || !(*options.smoothie_width > 0.0)))
    throw CLI::ValidationError("--smoothie-width", fmt::format("must be finite and > 0 (world units), got {}",
                                                               *options.smoothie_width));
  if (entry.reads(MethodOption::shadow_map) &&
      (options.shadowmap_size < 1 || options.shadowmap_size > gpu::kMaxShadowMapSize))
    throw CLI::ValidationError("--shadowmap-size", fmt::format("must be in [1, {}] (a {}^2 depth texture), got {}",
                                                               gpu::kMaxShadowMapSize, gpu::kMaxShadowMapSize,
                                                               options.shadowmap_size));
  return {method, stencil};
}

std::uint64_t count_pixels(const gpu::RgbaImage& colour, const gpu::GrayImage& stencil, bool lit) {
  std::uint64_t n = 0;
  for (std::size_t i = 0; i < stencil.pixels.size(); ++i) {
    const bool covered = colour.pixels[4 * i + 3] != 0;  // alpha 255 where a receiver was drawn
    if (covered && (stencil.pixels[i] == 0) == lit) ++n;
  }
  return n;
}

// ---- step 2: the scene as GL draws it ----------------------------------------------------------

struct DrawnScene {
  Scene scene;   // in its eye's frame
  Soup merged;   // every mesh: the receivers
  Soup casters;  // the meshes that cast (SceneMesh::casts): the volumes'
  gpu::SceneBounds bounds;
};

// GL is given the scene in its eye's frame (core/eye_frame.h; docs/diff.md): every position
// minus the eye in double, rounded once to float on upload.
DrawnScene load_drawn_scene(const RenderOptions& options) {
  Scene scene = load_image_scene(options.input);
  if (scene.lights.empty()) throw InputError(options.input, "the scene has no light");
  apply_image_size(options.size, scene.camera);
  DrawnScene d{eye_relative_scene(scene), {}, {}, {}};
  d.merged = merged_soup(d.scene);
  if (d.merged.triangles.empty()) throw InputError(options.input, "no triangle to render");
  d.casters = merged_casters(d.scene);
  d.bounds = gpu::soup_bounds(d.merged);
  return d;
}

// ---- step 3: the method's inputs ---------------------------------------------------------------

struct PreparedMethod {
  MethodInputs inputs;
  std::optional<SilhouetteVolumes> silhouette;  // discrete, accurate, smooth, smooth-gpu
  std::vector<LightStencil> stencils;           // the volume methods: each light's
  double light_radius = 0.0;                    // pcss: the point lights' disk radius
  double chain_seconds = 0.0, smoothie_seconds = 0.0, proof_seconds = 0.0;
};

PreparedMethod prepare_method(const DrawnScene& d, const ValidatedRenderOptions& v, const RenderOptions& options) {
  PreparedMethod p;
  // The methods' inputs (pipeline/method_inputs.h): the canonical soup and edge table (the
  // GPU-built methods read them), and for cpu one exact chain per light
  // (docs/definitions.md#counts) of the float-rounded input, as homogeneous floats.
  auto stage = Clock::now();
  const std::array methods{v.method};
  p.inputs = prepare_method_inputs(d.casters, d.scene.lights, methods);
  // discrete, accurate, smooth: each qualifying mesh's smooth-silhouette volume, the robust
  // chain of the others (pipeline/silhouette_volumes.h), drawn as cpu's volumes are; smooth-gpu:
  // the smooth casters for the GPU to build every frame, the others' volumes as given.
  if (gpu::is_silhouette_method(v.method)) {
    SilhouetteOptions silhouette_options = options.silhouette;
    silhouette_options.near_plane = d.scene.camera.near_plane;  // the scene is in the eye's frame
    p.silhouette = silhouette_volumes(d.scene.meshes, d.scene.lights, v.method, silhouette_options);
    p.inputs.cpu_volumes = p.silhouette->per_light;
    p.inputs.smooth_casters = p.silhouette->gpu_casters;
  }
  p.chain_seconds = seconds_since(stage);
  // smoothie: every light's smoothies on the CPU (pipeline/scene_smoothies.h), once.
  stage = Clock::now();
  if (v.method == gpu::ShadowMethod::smoothie) {
    SceneSmoothieOptions smoothie;
    smoothie.width = options.smoothie_width.value_or(0.0);
    smoothie.space = *parse_smoothie_space(options.smoothie_space.value_or("world"));  // CLI11 checked it
    add_smoothies(p.inputs, d.scene.lights, d.bounds, smoothie);
  }
  p.smoothie_seconds = seconds_since(stage);
  if (v.method == gpu::ShadowMethod::pcss) p.light_radius = options.light_radius.value_or(gpu::default_light_radius(d.bounds));
  // Each light's stencil method (pipeline/stencil_choice.h); auto proves z-pass per light at
  // the camera, exactly, on the float-rounded casters. The proof is about the exact chain: a
  // smooth-silhouette volume is counted with z-fail.
  stage = Clock::now();
  if (gpu::draws_volume(v.method))
    p.stencils = choose_stencil(p.silhouette ? StencilChoice::zfail : v.stencil, p.inputs, d.scene.lights,
                                d.scene.camera);
  p.proof_seconds = seconds_since(stage);
  return p;
}

// ---- step 4: the renderer's options ------------------------------------------------------------

gpu::ShadowMethodOptions renderer_options(const ValidatedRenderOptions& v, const PreparedMethod& p,
                                          const RenderOptions& options) {
  gpu::ShadowMethodOptions o;
  o.light_stencil = stencil_methods(p.stencils);
  if (gpu::uses_shadow_map(v.method)) o.shadow_map_size = static_cast<std::uint32_t>(options.shadowmap_size);
  o.shadow_map_bias = options.shadowmap_bias;
  o.shadow_map_slope = options.shadowmap_slope;
  o.sign = *gpu::parse_sign_mode(options.sign);  // CLI11 checked the name
  o.pcf_kernel = static_cast<std::uint32_t>(options.pcf.value_or(gpu::kDefaultPcfKernel));
  o.light_radius = p.light_radius;
  o.light_angle_degrees = options.light_angle.value_or(gpu::kDefaultLightAngleDegrees);
  // The first light's volume fill in the first frame (two occlusion queries; the timed frames
  // do without): what a method costs the rasteriser, whatever the machine.
  o.count_fragments = gpu::draws_volume(v.method);
  return o;
}

// ---- step 5: the frames ------------------------------------------------------------------------

struct RenderedFrames {
  gpu::StencilShadowFrame first;  // read back
  std::uint64_t volume_triangles = 0;
  double first_frame_seconds = 0.0;
  std::optional<gpu::FrameTiming> timing;  // --timing
  double frame_ms = 0.0;                   // mean wall ms of the timed frames
  std::size_t mean_frames = kPlainTimedFrames;
};

// The first frame, read back, then the timed ones. Throws gpu::VolumeCapacityError when a
// GPU-built volume overflowed its buffers in the first frame.
RenderedFrames render_frames(gpu::ShadowMethodRenderer& renderer, const gpu::OffscreenTarget& target,
                             const Camera& camera, const gpu::EglContext& context, const RenderOptions& options) {
  RenderedFrames f;
  const auto stage = Clock::now();
  f.first = renderer.render(target, camera);
  // GPU-built volumes are sized for the worst case but clamped to what storage blocks address:
  // the caller says so rather than report the image of a partial (open) volume.
  renderer.check_capacity();
  f.volume_triangles = renderer.volume_triangles();
  f.first_frame_seconds = seconds_since(stage);
  if (options.timing) {
    // A software renderer's timer queries do not time its stages (gpu/gpu_stage_timer.h):
    // there each stage is bounded by glFinish and timed on the wall clock as well.
    const gpu::StageSync sync = context.software() ? gpu::StageSync::finish : gpu::StageSync::none;
    f.timing = renderer.time_frames(target, camera, kTimingWarmUpFrames, options.frames, sync);
    f.frame_ms = f.timing->mean_cpu_ms;
    f.mean_frames = f.timing->frames;
  } else {
    const std::vector<double> wall_ms = renderer.render_frames(target, camera, kPlainTimedFrames);
    f.frame_ms = std::accumulate(wall_ms.begin(), wall_ms.end(), 0.0) / static_cast<double>(wall_ms.size());
  }
  return f;
}

// ---- step 6: the files -------------------------------------------------------------------------

void write_outputs(const RenderOptions& options, const Camera& camera, const RenderedFrames& f,
                   const gpu::ShadowMethodRenderer& renderer) {
  const gpu::StencilShadowFrame& frame = f.first;
  for (const std::string& file : {options.out, options.counts, options.mask}) create_parent_directories(file);
  if (!options.light_image.empty()) write_light_image(options.light_image, camera.width, camera.height, frame.first_light);
  if (!options.out.empty()) gpu::write_png(options.out, frame.colour);
  if (!options.counts.empty()) gpu::write_png(options.counts, frame.first_stencil);
  if (!options.mask.empty()) gpu::write_png(options.mask, frame.first_lit_mask);
  if (!options.capture.empty()) {  // what was drawn, so that certify --volume checks the GPU's own output
    create_parent_directories(options.capture);
    write_volume_file(options.capture, renderer.first_volume(),
                      options.input + ", method " + options.method + ", first light");
  }
}

// ---- step 7: the report ------------------------------------------------------------------------

// Everything the report says, gathered once for the text and the JSON.
struct RenderReport {
  const RenderOptions& options;
  const ValidatedRenderOptions& v;
  const DrawnScene& d;
  const PreparedMethod& p;
  const gpu::ShadowMethodOptions& method_options;
  const RenderedFrames& f;
  const gpu::EglContext& context;
  double upload_seconds = 0.0;
  double seconds = 0.0;
  std::uint64_t lit = 0, shadowed = 0;
  // The shadow-map methods' lights that one frustum cannot hold (a point light inside or next to
  // the scene's bounds): drawn with a cube map (gpu/shadow_map_renderer.h's light_views).
  std::vector<std::size_t> cube_lights;
};

// The shadow-map family's parameters, as the registry says each method reads them.
std::string shadow_map_parameters_text(const RenderReport& r) {
  const MethodEntry& entry = method_entry(r.v.method);
  std::string text = fmt::format("{}^2 (bias {}, slope {})", r.options.shadowmap_size, r.options.shadowmap_bias,
                                 r.options.shadowmap_slope);
  if (entry.reads(MethodOption::pcf_kernel))
    text += fmt::format(", pcf {}x{}", r.method_options.pcf_kernel, r.method_options.pcf_kernel);
  if (entry.reads(MethodOption::light_radius))
    text += fmt::format(", light radius {:.6g} (point), angle {:.6g} degrees (directional)", r.p.light_radius,
                        r.method_options.light_angle_degrees);
  if (entry.reads(MethodOption::smoothie))
    text += fmt::format(", smoothies {:.6g} wide in {} space", r.p.inputs.smoothies.width,
                        smoothie_space_name(r.p.inputs.smoothies.space));
  return text;
}

void print_report(const RenderReport& r) {
  const Scene& scene = r.d.scene;
  const bool shadowmap = gpu::uses_shadow_map(r.v.method);
  const std::string triangles =
      r.d.casters.triangles.size() == r.d.merged.triangles.size()
          ? fmt::format("{} triangles", r.d.merged.triangles.size())
          : fmt::format("{} triangles ({} cast)", r.d.merged.triangles.size(), r.d.casters.triangles.size());
  if (shadowmap) {
    fmt::print("{}: {}, {} lights, {}x{}, {} {} on {}\n", r.options.input, triangles, scene.lights.size(),
               scene.camera.width, scene.camera.height, gpu::shadow_method_name(r.v.method),
               shadow_map_parameters_text(r), r.context.renderer());
    for (std::size_t k : r.cube_lights)
      fmt::print("  light {}: inside or next to the scene's bounds: a cube map (six 90-degree faces)\n", k);
    if (r.v.method == gpu::ShadowMethod::smoothie && !r.p.inputs.smoothies.stats.empty()) {
      const SmoothieStats& st = r.p.inputs.smoothies.stats.front();
      fmt::print("  smoothies (first light): {} silhouette edges, {} quads, {} linked and {} shrunk corners, "
                 "{} zero-length and {} edge-on edges skipped, {} bisector fallbacks; {:.3f} s\n",
                 st.edges, st.smoothies, st.linked_corners, st.shrunk_corners, st.zero_length_edges,
                 st.edge_on_edges, st.bisector_fallbacks, r.p.smoothie_seconds);
    }
  } else {
    fmt::print("{}: {}, {} lights, {}x{}, {}/{} on {}\n", r.options.input, triangles, scene.lights.size(),
               scene.camera.width, scene.camera.height, r.options.method, stencil_choice_name(r.v.stencil),
               r.context.renderer());
    print_stencil(r.p.stencils);
    if (r.p.silhouette) print_silhouette_casters(*r.p.silhouette);
    fmt::print("  volume triangles (first light) {}; its fill: {} fragments, {} stencil updates\n",
               r.f.volume_triangles, r.f.first.first_volume_fragments, r.f.first.first_stencil_updates);
  }
  fmt::print("  first light: {} lit, {} shadowed receiver pixels\n", r.lit, r.shadowed);
  fmt::print("  seconds: {}upload {:.3f}, first frame {:.3f}; {:.2f} ms per frame ({} frames)\n",
             shadowmap ? "" : fmt::format("chains {:.3f}, ", r.p.chain_seconds), r.upload_seconds,
             r.f.first_frame_seconds, r.f.frame_ms, r.f.mean_frames);
  if (r.f.timing) print_frame_timing(*r.f.timing, kTimingWarmUpFrames);
}

nlohmann::json report_json(const RenderReport& r) {
  const Scene& scene = r.d.scene;
  const MethodEntry& entry = method_entry(r.v.method);
  nlohmann::json report{{"input", r.options.input},
                        {"method", entry.name()},
                        {"size", {scene.camera.width, scene.camera.height}},
                        {"renderer", r.context.renderer()},
                        {"device", r.context.device()},
                        {"lights", scene.lights.size()},
                        {"lit_pixels", r.lit},
                        {"shadowed_pixels", r.shadowed},
                        {"frame_ms", r.f.frame_ms},
                        {"seconds", r.seconds}};
  if (!r.options.light_image.empty())
    report["light_image"] = {{"png", r.options.light_image},
                             {"pfm", light_image_float_path(r.options.light_image).string()}};
  if (gpu::uses_shadow_map(r.v.method)) {
    report["shadowmap"] = {
        {"size", r.options.shadowmap_size}, {"bias", r.options.shadowmap_bias}, {"slope", r.options.shadowmap_slope}};
    report["stage_seconds"] = {{"upload", r.upload_seconds}, {"first_frame", r.f.first_frame_seconds}};
    report["cube_lights"] = r.cube_lights;
    if (entry.reads(MethodOption::pcf_kernel)) report["pcf_kernel"] = r.method_options.pcf_kernel;
    if (entry.reads(MethodOption::light_radius)) {
      report["light_radius"] = r.p.light_radius;
      report["light_angle_degrees"] = r.method_options.light_angle_degrees;
    }
    if (entry.reads(MethodOption::smoothie)) {
      nlohmann::json per_light = nlohmann::json::array();
      for (const SmoothieStats& st : r.p.inputs.smoothies.stats)
        per_light.push_back({{"silhouette_edges", st.edges},
                             {"smoothies", st.smoothies},
                             {"linked_corners", st.linked_corners},
                             {"shrunk_corners", st.shrunk_corners},
                             {"zero_length_edges", st.zero_length_edges},
                             {"edge_on_edges", st.edge_on_edges},
                             {"bisector_fallbacks", st.bisector_fallbacks}});
      report["smoothie"] = {{"width", r.p.inputs.smoothies.width},
                            {"space", smoothie_space_name(r.p.inputs.smoothies.space)},
                            {"per_light", per_light}};
      report["stage_seconds"]["smoothies"] = r.p.smoothie_seconds;
    }
  } else {
    report["stencil"] = stencil_choice_name(r.v.stencil);
    report["stencil_per_light"] = stencil_json(r.p.stencils);
    report["volume_triangles"] = r.f.volume_triangles;
    report["volume_fragments"] = r.f.first.first_volume_fragments;
    report["stencil_updates"] = r.f.first.first_stencil_updates;
    report["stage_seconds"] = {
        {"chains", r.p.chain_seconds}, {"upload", r.upload_seconds}, {"first_frame", r.f.first_frame_seconds}};
    if (r.v.stencil == StencilChoice::automatic) report["stage_seconds"]["zpass_proof"] = r.p.proof_seconds;
    if (r.p.silhouette) report["casters"] = silhouette_casters_json(*r.p.silhouette);
  }
  if (r.f.timing) report["timing"] = frame_timing_json(*r.f.timing, kTimingWarmUpFrames);
  return report;
}

// ---- a ray-traced method (rt, rt-robust): no GL, the same files ---------------------------------

// The options a ray-traced method reads are the scene's, the size and the files of the first
// light (--out, --mask, --light-image, --json); every GL option given is refused by name.
void refuse_gl_options(const RenderOptions& options, const RayTracedEntry& entry) {
  const auto refuse = [&](bool given, const char* flag, const char* readers) {
    if (given)
      throw CLI::ValidationError(flag, fmt::format("is read by {} only; --method {} (Embree on the CPU) does not "
                                                   "read it", readers, entry.name));
  };
  refuse(options.pcf.has_value(), "--pcf", "pcf");
  refuse(options.pcss, "--pcss", "pcss");
  refuse(options.light_radius.has_value(), "--light-radius", methods_reading(MethodOption::light_radius).c_str());
  refuse(options.light_angle.has_value(), "--light-angle", methods_reading(MethodOption::light_radius).c_str());
  refuse(options.smoothie_width.has_value(), "--smoothie-width", "smoothie");
  refuse(options.smoothie_space.has_value(), "--smoothie-space", "smoothie");
  refuse(!options.capture.empty(), "--capture", "the volume methods");
  refuse(!options.stencil.empty() || options.zpass || options.zfail, "--stencil", "the volume methods");
  refuse(!options.counts.empty(), "--counts", "the volume methods (stencil counts)");
  refuse(options.timing, "--timing", "the GL methods (GPU stage times)");
  refuse(options.device.has_value(), "--device", "the GL methods");
}

int run_ray_traced_render(const RenderOptions& options, const RayTracedEntry& entry) {
  const auto start = Clock::now();
  refuse_gl_options(options, entry);
  Scene scene = load_image_scene(options.input);
  if (scene.lights.empty()) throw InputError(options.input, "the scene has no light");
  apply_image_size(options.size, scene.camera);
  const std::size_t triangles = merged_soup(scene).triangles.size();
  if (triangles == 0) throw InputError(options.input, "no triangle to render");
  // World space, as the exact image: a user's ray tracer takes the scene as it is.
  const raytrace::RayTracedImage image = ray_traced_scene_image(scene, entry.method, options.threads);
  const gpu::StencilShadowFrame frame = ray_traced_frame(scene, image, 0);
  for (const std::string& file : {options.out, options.mask}) create_parent_directories(file);
  if (!options.light_image.empty())
    write_light_image(options.light_image, scene.camera.width, scene.camera.height, frame.first_light);
  if (!options.out.empty()) gpu::write_png(options.out, frame.colour);
  if (!options.mask.empty()) gpu::write_png(options.mask, frame.first_lit_mask);
  std::uint64_t lit = 0, shadowed = 0;
  for (std::size_t p = 0; p < image.hit_triangles.size(); ++p)
    if (image.hit_triangles[p] != raytrace::kMissed) ++(image.lit[0][p] != 0 ? lit : shadowed);
  const std::string mode(raytrace::build_mode_name(entry.mode));
  fmt::print("{}: {} triangles, {} lights, {}x{}, {} (Embree {} mode on the CPU)\n", options.input, triangles,
             scene.lights.size(), scene.camera.width, scene.camera.height, entry.name, mode);
  fmt::print("  first light: {} lit, {} shadowed receiver pixels\n", lit, shadowed);
  fmt::print("  seconds: build {:.3f}, trace {:.3f} ({} rays, {} shadow rays), all {:.3f}\n",
             image.stats.build_seconds, image.stats.trace_seconds, image.stats.rays, image.stats.shadow_rays,
             image.stats.seconds);
  if (!options.json_file.empty()) {
    nlohmann::json report{{"input", options.input},
                          {"method", entry.name},
                          {"size", {scene.camera.width, scene.camera.height}},
                          {"renderer", "Embree (CPU), " + mode + " mode"},
                          {"lights", scene.lights.size()},
                          {"lit_pixels", lit},
                          {"shadowed_pixels", shadowed},
                          {"frame_ms", 1000.0 * (image.stats.build_seconds + image.stats.trace_seconds)},
                          {"stage_seconds",
                           {{"build", image.stats.build_seconds}, {"trace", image.stats.trace_seconds}}},
                          {"rays", image.stats.rays},
                          {"shadow_rays", image.stats.shadow_rays},
                          {"seconds", seconds_since(start)}};
    if (!options.light_image.empty())
      report["light_image"] = {{"png", options.light_image},
                               {"pfm", light_image_float_path(options.light_image).string()}};
    write_json_file(options.json_file, report);
  }
  return kExitOk;
}

// ---- the command: the steps in order -----------------------------------------------------------

int run_render(const RenderOptions& options) {
  if (const RayTracedEntry* entry = find_ray_traced_method(options.method)) return run_ray_traced_render(options, *entry);
  if (options.threads != 0)
    throw CLI::ValidationError("--threads", "only the ray-traced methods (rt, rt-robust) run on CPU threads; " +
                                                options.method + " renders with GL");
  const auto start = Clock::now();
  const ValidatedRenderOptions v = validate(options);                 // 1. the options
  const DrawnScene d = load_drawn_scene(options);                     // 2. the scene
  const PreparedMethod p = prepare_method(d, v, options);             // 3. the method's inputs
  const gpu::EglContext context = gpu::open_gl_context("render", options.device);
  auto stage = Clock::now();                                          // 4. the renderer
  const std::vector<gpu::ShadedSoupPart> parts = shaded_parts(d.scene);
  const gpu::ShadowMethodOptions method_options = renderer_options(v, p, options);
  gpu::ShadowMethodRenderer renderer(v.method, method_scene(p.inputs, parts, d.scene.lights), method_options);
  const gpu::OffscreenTarget target(d.scene.camera.width, d.scene.camera.height);
  const double upload_seconds = seconds_since(stage);
  RenderedFrames f;                                                   // 5. the frames
  try {
    f = render_frames(renderer, target, d.scene.camera, context, options);
  } catch (const gpu::VolumeCapacityError& e) {
    // As in diff, where the same overflow is recorded and fails the method, it is the method
    // failing on this input (exit 1), not an error in the input (docs/cli.md, "Exit codes").
    fmt::print(stderr, "shadowcert render: {}: {}; nothing written\n", options.input, e.what());
    return kExitCheckFailed;
  }
  write_outputs(options, d.scene.camera, f, renderer);                // 6. the files
  RenderReport r{options, v, d, p, method_options, f, context, 0.0, 0.0, 0, 0, {}};  // 7. the report
  r.upload_seconds = upload_seconds;
  r.lit = count_pixels(f.first.colour, f.first.first_stencil, true);
  r.shadowed = count_pixels(f.first.colour, f.first.first_stencil, false);
  if (gpu::uses_shadow_map(v.method))
    for (std::size_t k = 0; k < d.scene.lights.size(); ++k)
      if (gpu::needs_cube_map(d.scene.lights[k], d.bounds)) r.cube_lights.push_back(k);
  r.seconds = seconds_since(start);
  print_report(r);
  if (!options.json_file.empty()) write_json_file(options.json_file, report_json(r));
  return kExitOk;
}

}  // namespace

void add_render_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<RenderOptions>();
  CLI::App* cmd = app.add_subcommand(
      "render",
      "Stencil shadow volumes with OpenGL 4.5 core (headless EGL; docs/definitions.md#counts, 5). Lights are drawn one after "
      "another; --counts, --mask and the pixel counts are for the FIRST light");
  cmd->add_option("input", options->input, kImageInputHelp)->required();
  std::vector<std::string> method_names_list;
  for (const MethodEntry& e : method_registry()) method_names_list.emplace_back(e.name());
  for (const RayTracedEntry& e : ray_traced_registry()) method_names_list.emplace_back(e.name);
  cmd->add_option("--method", options->method, method_help())
      ->check(CLI::IsMember(method_names_list))
      ->capture_default_str();
  add_silhouette_options(*cmd, options->silhouette);
  cmd->add_option("--stencil", options->stencil,
                  "Stencil counting of the volume methods: zfail (default; faces behind the visible point, right "
                  "wherever the eye is), zpass (faces in front of it; wrong with the eye in a volume) or auto (per "
                  "light, zpass where it is proven exactly for this camera, else zfail; the reasons are printed and "
                  "written to --json)")
      ->check(CLI::IsMember({"auto", "zpass", "zfail"}));
  cmd->add_flag("--zfail", options->zfail, "Alias of --stencil zfail");
  cmd->add_flag("--zpass", options->zpass, "Alias of --stencil zpass");
  cmd->add_option("--size", options->size, "Image size WxH (default: the scene camera's)");
  cmd->add_option("--out", options->out, "Write the shaded image (RGBA PNG; alpha 0 where no surface)");
  cmd->add_option("--counts", options->counts, "Write the first light's stencil counts mod 256 (8-bit gray PNG)");
  cmd->add_option("--mask", options->mask, "Write the first light's lit mask (255 where the count is 0)");
  cmd->add_option("--json", options->json_file, "Write method, size, renderer, pixel counts and timings as JSON");
  cmd->add_option("--capture", options->capture,
                  "Write the first light's volume as drawn (.vol text; check it with certify --volume FILE)");
  cmd->add_option("--shadowmap-size", options->shadowmap_size,
                  "shadowmap, pcf, pcss, smoothie: side of the square depth map (and smoothie map) in texels, at "
                  "most 16384")
      ->capture_default_str();
  cmd->add_option("--sign", options->sign, "cs, gs, ts, pertri: each triangle's light side as the exact sign of its float inputs (exact: a proven float filter, integer arithmetic where it cannot decide) or the float formula's sign (float: Milet 2014 refedge, wrong where the light is within rounding of a plane)")
      ->check(CLI::IsMember({"exact", "float"}))
      ->capture_default_str();
  cmd->add_option("--shadowmap-bias", options->shadowmap_bias,
                  "shadowmap, pcf, pcss, smoothie: constant bias subtracted from the light-space depth (window units, [0, 1]) "
                  "before the comparison; larger trades acne for detached shadows")
      ->capture_default_str();
  cmd->add_option("--shadowmap-slope", options->shadowmap_slope,
                  "shadowmap, pcf, pcss, smoothie: glPolygonOffset slope factor of the depth pass (for surfaces edge-on to the light)")
      ->capture_default_str();
  CLI::Option* timing = cmd->add_flag(
      "--timing", options->timing,
      "Time each stage on the GPU (GL_TIME_ELAPSED: volume build, depth, stencil, lit; shadowmap: depth, "
      "shadow_map, lit) and each frame (GPU and CPU wall), after 2 warm-up frames; print median, min and max, "
      "and add them to --json under \"timing\"");
  cmd->add_option("--frames", options->frames, "--timing: how many frames to time")
      ->check(CLI::Range(std::size_t{1}, std::size_t{100000}))
      ->needs(timing)
      ->capture_default_str();
  cmd->add_option("--pcf", options->pcf,
                  "Percentage-closer filtering: K x K depth comparisons centred on the point's texel, K odd in "
                  "[1, 15] (1: the hard map). Picks --method pcf (which alone uses K = 3)");
  cmd->add_flag("--pcss", options->pcss,
                "Percentage-closer soft shadows (Fernando 2005: blocker search, then PCF over the predicted "
                "penumbra) for a disk light of radius --light-radius around a point light, of angular radius --light-angle for "
                "a directional one. Same as --method pcss");
  cmd->add_option("--light-radius", options->light_radius,
                  "pcss: a point light's radius R in world units (the soft reference's disk light); default 1% of "
                  "the scene's bounding-box diagonal; directional lights take --light-angle");
  cmd->add_option("--light-angle", options->light_angle, std::string("pcss: ") + kLightAngleHelp);
  cmd->add_option("--smoothie-width", options->smoothie_width,
                  "smoothie: the smoothies' width D in world units (light space: at the distance from the light to "
                  "the scene's centre); default 2% of the scene's bounding-box diagonal");
  cmd->add_option("--smoothie-space", options->smoothie_space,
                  "smoothie: world (Chen & Tsai: along the bisector of the edge's faces, D wide) or light (Chan & "
                  "Durand: perpendicular to the light's rays, a constant width in the light's image); default world")
      ->check(CLI::IsMember({"world", "light"}));
  cmd->add_option("--light-image", options->light_image,
                  "Write the first light's amount of light per pixel: FILE.png (8-bit gray, 255 lit, 0 shadowed, "
                  "between in a penumbra, 0 where no surface) and FILE.pfm beside it (32-bit floats, -1 where no "
                  "surface); every method");
  cmd->add_option("--device", options->device, "Use EGL device N (default: a hardware device, else llvmpipe)");
  cmd->add_option("--threads", options->threads, "rt, rt-robust: the ray tracer's threads (TBB; 0: every core)")
      ->capture_default_str();
  CLI::Option* method_option = cmd->get_option("--method");
  cmd->callback([options, method_option, &exit_code] {
    options->method_given = method_option->count() > 0;
    exit_code = run_render(*options);
  });
}

}  // namespace shadowcert::cli
