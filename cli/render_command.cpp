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
  if (options.light_radius) {
    if (method != gpu::ShadowMethod::pcss)
      throw CLI::ValidationError("--light-radius", "is pcss's light size: use it with --pcss or --method pcss");
    if (!std::isfinite(*options.light_radius) || !(*options.light_radius > 0.0))
      throw CLI::ValidationError("--light-radius",
                                 fmt::format("must be finite and > 0 (world units), got {}", *options.light_radius));
  }
  if (options.light_angle) {
    if (method != gpu::ShadowMethod::pcss)
      throw CLI::ValidationError("--light-angle", "is pcss's light size: use it with --pcss or --method pcss");
    check_light_angle(*options.light_angle);
  }
  if (options.smoothie_width) {
    if (method != gpu::ShadowMethod::smoothie)
      throw CLI::ValidationError("--smoothie-width", "is the smoothie method's: use it with --method smoothie");
    if (!std::isfinite(*options.smoothie_width) || !(*options.smoothie_width > 0.0))
      throw CLI::ValidationError("--smoothie-width", fmt::format("must be finite and > 0 (world units), got {}",
                                                                 *options.smoothie_width));
  }
  if (options.smoothie_space && method != gpu::ShadowMethod::smoothie)
    throw CLI::ValidationError("--smoothie-space", "is the smoothie method's: use it with --method smoothie");
  if (gpu::uses_shadow_map(method)) {
    if (options.shadowmap_size < 1 || options.shadowmap_size > gpu::kMaxShadowMapSize)
      throw CLI::ValidationError("--shadowmap-size", fmt::format("must be in [1, {}] (a {}^2 depth texture), got {}",
                                                                 gpu::kMaxShadowMapSize, gpu::kMaxShadowMapSize,
                                                                 options.shadowmap_size));
    const std::string_view name = gpu::shadow_method_name(method);
    if (stencil != StencilChoice::zfail)
      throw CLI::ValidationError(options.zpass ? "--zpass" : "--stencil",
                                 fmt::format("is a stencil option; {} counts no volume", name));
    if (!options.capture.empty())
      throw CLI::ValidationError("--capture", fmt::format("{} draws no volume to capture", name));
  }
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

int run_render(const RenderOptions& options) {
  const auto start = Clock::now();
  const auto [method, stencil_choice] = validate(options);
  const bool shadowmap = gpu::uses_shadow_map(method);  // shadowmap, pcf, pcss, smoothie
  Scene scene = load_image_scene(options.input);
  if (scene.lights.empty()) throw InputError(options.input, "the scene has no light");
  apply_image_size(options.size, scene.camera);
  // GL is given the scene in its eye's frame (core/eye_frame.h; docs/diff.md): every position
  // minus the eye in double, rounded once to float on upload.
  scene = eye_relative_scene(scene);
  const Soup merged = merged_soup(scene);
  if (merged.triangles.empty()) throw InputError(options.input, "no triangle to render");
  // Every mesh is drawn; only the casting ones (SceneMesh::casts) make the volumes.
  const Soup casters = merged_casters(scene);

  // The methods' inputs (pipeline/method_inputs.h): the canonical soup and edge table (the
  // GPU-built methods read them), and for cpu one exact chain per light
  // (docs/definitions.md#counts) of the float-rounded input, as homogeneous floats.
  auto stage = Clock::now();
  const std::array methods{method};
  MethodInputs inputs = prepare_method_inputs(casters, scene.lights, methods);
  // discrete, accurate, smooth: each qualifying mesh's smooth-silhouette volume, the robust
  // chain of the others (pipeline/silhouette_volumes.h), drawn as cpu's volumes are; smooth-gpu:
  // the smooth casters for the GPU to build every frame, the others' volumes as given.
  std::optional<SilhouetteVolumes> silhouette;
  if (gpu::is_silhouette_method(method)) {
    SilhouetteOptions silhouette_options = options.silhouette;
    silhouette_options.near_plane = scene.camera.near_plane;  // the scene is in the eye's frame
    silhouette = silhouette_volumes(scene.meshes, scene.lights, method, silhouette_options);
    inputs.cpu_volumes = silhouette->per_light;
    inputs.smooth_casters = silhouette->gpu_casters;
  }
  const double chain_seconds = seconds_since(stage);
  // smoothie: every light's smoothies on the CPU (pipeline/scene_smoothies.h), once.
  const gpu::SceneBounds bounds = gpu::soup_bounds(merged);
  stage = Clock::now();
  if (method == gpu::ShadowMethod::smoothie) {
    SceneSmoothieOptions smoothie;
    smoothie.width = options.smoothie_width.value_or(0.0);
    smoothie.space = *parse_smoothie_space(options.smoothie_space.value_or("world"));  // CLI11 checked it
    add_smoothies(inputs, scene.lights, bounds, smoothie);
  }
  const double smoothie_seconds = seconds_since(stage);
  const double light_radius =
      method == gpu::ShadowMethod::pcss ? options.light_radius.value_or(gpu::default_light_radius(bounds)) : 0.0;

  // Each light's stencil method (pipeline/stencil_choice.h); auto proves z-pass per light at
  // the camera, exactly, on the float-rounded casters.
  stage = Clock::now();
  std::vector<LightStencil> stencils;
  // The z-pass proof is about the exact chain: a smooth-silhouette volume is counted with z-fail.
  if (!shadowmap) stencils = choose_stencil(silhouette ? StencilChoice::zfail : stencil_choice, inputs, scene.lights,
                                            scene.camera);
  const double proof_seconds = seconds_since(stage);

  const gpu::EglContext context = gpu::open_gl_context("render", options.device);

  stage = Clock::now();
  const std::vector<gpu::ShadedSoupPart> parts = shaded_parts(scene);
  const gpu::ShadowMethodScene method_scene_ = method_scene(inputs, parts, scene.lights);
  gpu::ShadowMethodOptions method_options;
  method_options.light_stencil = stencil_methods(stencils);
  if (shadowmap) method_options.shadow_map_size = static_cast<std::uint32_t>(options.shadowmap_size);
  method_options.shadow_map_bias = options.shadowmap_bias;
  method_options.sign = *gpu::parse_sign_mode(options.sign);  // CLI11 checked the name
  method_options.shadow_map_slope = options.shadowmap_slope;
  method_options.pcf_kernel = static_cast<std::uint32_t>(options.pcf.value_or(gpu::kDefaultPcfKernel));
  method_options.light_radius = light_radius;
  method_options.light_angle_degrees = options.light_angle.value_or(gpu::kDefaultLightAngleDegrees);
  // The first light's volume fill in the first frame (two occlusion queries; the timed frames
  // do without): what a method costs the rasteriser, whatever the machine.
  method_options.count_fragments = !shadowmap;
  gpu::ShadowMethodRenderer renderer(method, method_scene_, method_options);
  const gpu::OffscreenTarget target(scene.camera.width, scene.camera.height);
  const double upload_seconds = seconds_since(stage);

  stage = Clock::now();
  const gpu::StencilShadowFrame frame = renderer.render(target, scene.camera);
  try {
    // GPU-built volumes are sized for the worst case but clamped to what storage blocks
    // address: say so rather than report the image of a partial (open) volume. As in diff,
    // where the same overflow is recorded and fails the method, it is the method failing on
    // this input (exit 1), not an error in the input (docs/cli.md, "Exit codes").
    renderer.check_capacity();
  } catch (const gpu::VolumeCapacityError& e) {
    fmt::print(stderr, "shadowcert render: {}: {}; nothing written\n", options.input, e.what());
    return kExitCheckFailed;
  }
  const std::uint64_t volume_triangles = renderer.volume_triangles();
  const double first_frame_seconds = seconds_since(stage);

  std::optional<gpu::FrameTiming> timing;
  double frame_ms = 0.0;
  std::size_t mean_frames = kPlainTimedFrames;
  if (options.timing) {
    // A software renderer's timer queries do not time its stages (gpu/gpu_stage_timer.h):
    // there each stage is bounded by glFinish and timed on the wall clock as well.
    const gpu::StageSync sync = context.software() ? gpu::StageSync::finish : gpu::StageSync::none;
    timing = renderer.time_frames(target, scene.camera, kTimingWarmUpFrames, options.frames, sync);
    frame_ms = timing->mean_cpu_ms;
    mean_frames = timing->frames;
  } else {
    const std::vector<double> wall_ms = renderer.render_frames(target, scene.camera, kPlainTimedFrames);
    frame_ms = std::accumulate(wall_ms.begin(), wall_ms.end(), 0.0) / static_cast<double>(wall_ms.size());
  }

  for (const std::string& file : {options.out, options.counts, options.mask}) create_parent_directories(file);
  if (!options.light_image.empty())
    write_light_image(options.light_image, scene.camera.width, scene.camera.height, frame.first_light);
  if (!options.out.empty()) gpu::write_png(options.out, frame.colour);
  if (!options.counts.empty()) gpu::write_png(options.counts, frame.first_stencil);
  if (!options.mask.empty()) gpu::write_png(options.mask, frame.first_lit_mask);
  if (!options.capture.empty()) {  // what was drawn, so that certify --volume checks the GPU's own output
    create_parent_directories(options.capture);
    write_volume_file(options.capture, renderer.first_volume(),
                          options.input + ", method " + options.method + ", first light");
  }
  const std::uint64_t lit = count_pixels(frame.colour, frame.first_stencil, true);
  const std::uint64_t shadowed = count_pixels(frame.colour, frame.first_stencil, false);
  const double seconds = seconds_since(start);

  const std::string_view stencil = stencil_choice_name(stencil_choice);
  const std::string triangles =
      casters.triangles.size() == merged.triangles.size()
          ? fmt::format("{} triangles", merged.triangles.size())
          : fmt::format("{} triangles ({} cast)", merged.triangles.size(), casters.triangles.size());
  // The shadow-map methods' lights that one frustum cannot hold (a point light inside or next to
  // the scene's bounds): drawn with a cube map (gpu/shadow_map_renderer.h's light_views).
  std::vector<std::size_t> cube_lights;
  if (shadowmap)
    for (std::size_t k = 0; k < scene.lights.size(); ++k)
      if (gpu::needs_cube_map(scene.lights[k], bounds)) cube_lights.push_back(k);
  if (shadowmap) {
    std::string filter;
    if (method == gpu::ShadowMethod::pcf) filter = fmt::format(", pcf {}x{}", method_options.pcf_kernel, method_options.pcf_kernel);
    if (method == gpu::ShadowMethod::pcss)
      filter = fmt::format(", pcss light radius {:.6g} (point), angle {:.6g} degrees (directional)", light_radius,
                           method_options.light_angle_degrees);
    if (method == gpu::ShadowMethod::smoothie)
      filter = fmt::format(", smoothies {:.6g} wide in {} space", inputs.smoothies.width,
                           smoothie_space_name(inputs.smoothies.space));
    fmt::print("{}: {}, {} lights, {}x{}, {} {}^2 (bias {}, slope {}){} on {}\n", options.input, triangles,
               scene.lights.size(), scene.camera.width, scene.camera.height, gpu::shadow_method_name(method),
               options.shadowmap_size, options.shadowmap_bias, options.shadowmap_slope, filter, context.renderer());
    for (std::size_t k : cube_lights)
      fmt::print("  light {}: inside or next to the scene's bounds: a cube map (six 90-degree faces)\n", k);
    if (method == gpu::ShadowMethod::smoothie && !inputs.smoothies.stats.empty()) {
      const SmoothieStats& st = inputs.smoothies.stats.front();
      fmt::print("  smoothies (first light): {} silhouette edges, {} quads, {} linked and {} shrunk corners, "
                 "{} zero-length and {} edge-on edges skipped, {} bisector fallbacks; {:.3f} s\n",
                 st.edges, st.smoothies, st.linked_corners, st.shrunk_corners, st.zero_length_edges,
                 st.edge_on_edges, st.bisector_fallbacks, smoothie_seconds);
    }
  } else {
    fmt::print("{}: {}, {} lights, {}x{}, {}/{} on {}\n", options.input, triangles, scene.lights.size(),
               scene.camera.width, scene.camera.height, options.method, stencil, context.renderer());
    print_stencil(stencils);
    if (silhouette) print_silhouette_casters(*silhouette);
    fmt::print("  volume triangles (first light) {}; its fill: {} fragments, {} stencil updates\n", volume_triangles,
               frame.first_volume_fragments, frame.first_stencil_updates);
  }
  fmt::print("  first light: {} lit, {} shadowed receiver pixels\n", lit, shadowed);
  fmt::print("  seconds: {}upload {:.3f}, first frame {:.3f}; {:.2f} ms per frame ({} frames)\n",
             shadowmap ? "" : fmt::format("chains {:.3f}, ", chain_seconds), upload_seconds, first_frame_seconds,
             frame_ms, mean_frames);
  if (timing) print_frame_timing(*timing, kTimingWarmUpFrames);

  if (!options.json_file.empty()) {
    nlohmann::json report{{"input", options.input},
                          {"method", gpu::shadow_method_name(method)},
                          {"size", {scene.camera.width, scene.camera.height}},
                          {"renderer", context.renderer()},
                          {"device", context.device()},
                          {"lights", scene.lights.size()},
                          {"lit_pixels", lit},
                          {"shadowed_pixels", shadowed},
                          {"frame_ms", frame_ms},
                          {"seconds", seconds}};
    if (!options.light_image.empty())
      report["light_image"] = {{"png", options.light_image},
                               {"pfm", light_image_float_path(options.light_image).string()}};
    if (shadowmap) {
      report["shadowmap"] = {
          {"size", options.shadowmap_size}, {"bias", options.shadowmap_bias}, {"slope", options.shadowmap_slope}};
      report["stage_seconds"] = {{"upload", upload_seconds}, {"first_frame", first_frame_seconds}};
      report["cube_lights"] = cube_lights;
      if (method == gpu::ShadowMethod::pcf) report["pcf_kernel"] = method_options.pcf_kernel;
      if (method == gpu::ShadowMethod::pcss) {
        report["light_radius"] = light_radius;
        report["light_angle_degrees"] = method_options.light_angle_degrees;
      }
      if (method == gpu::ShadowMethod::smoothie) {
        nlohmann::json per_light = nlohmann::json::array();
        for (const SmoothieStats& st : inputs.smoothies.stats)
          per_light.push_back({{"silhouette_edges", st.edges},
                               {"smoothies", st.smoothies},
                               {"linked_corners", st.linked_corners},
                               {"shrunk_corners", st.shrunk_corners},
                               {"zero_length_edges", st.zero_length_edges},
                               {"edge_on_edges", st.edge_on_edges},
                               {"bisector_fallbacks", st.bisector_fallbacks}});
        report["smoothie"] = {{"width", inputs.smoothies.width},
                              {"space", smoothie_space_name(inputs.smoothies.space)},
                              {"per_light", per_light}};
        report["stage_seconds"]["smoothies"] = smoothie_seconds;
      }
    } else {
      report["stencil"] = stencil;
      report["stencil_per_light"] = stencil_json(stencils);
      report["volume_triangles"] = volume_triangles;
      report["volume_fragments"] = frame.first_volume_fragments;
      report["stencil_updates"] = frame.first_stencil_updates;
      report["stage_seconds"] = {
          {"chains", chain_seconds}, {"upload", upload_seconds}, {"first_frame", first_frame_seconds}};
      if (stencil_choice == StencilChoice::automatic) report["stage_seconds"]["zpass_proof"] = proof_seconds;
      if (silhouette) report["casters"] = silhouette_casters_json(*silhouette);
    }
    if (timing) report["timing"] = frame_timing_json(*timing, kTimingWarmUpFrames);
    write_json_file(options.json_file, report);
  }
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
  cmd->add_option("--method", options->method,
                  "How the volume is built: cpu (the exact chain of the float-rounded input from exact/, drawn as "
                  "is; exact/cpu_volume.h), cs (compute "
                  "shader, float reference-edge multiplicities, rebuilt every frame; gpu/compute_volume.h), "
                  "pertri (compute shader, every triangle's closed volume, no silhouette, rebuilt every frame; "
                  "gpu/per_triangle_volume.h), gs (geometry shader over edge records, float reference-edge "
                  "multiplicities, captured by transform feedback, rebuilt every frame; "
                  "gpu/geometry_shader_volume.h) or ts (tessellation over edge-record patches, the same "
                  "multiplicities and capture; gpu/tessellation_volume.h). shadowmap (no volume: a depth map "
                  "from each light, --shadowmap-size/-bias/-slope; gpu/shadow_map_renderer.h); pcf, pcss (the map "
                  "filtered: --pcf K, --pcss, --light-radius) and smoothie (the map, then smoothies along the "
                  "silhouette edges: --smoothie-width, --smoothie-space; docs/smoothies.md). discrete, accurate, "
                  "smooth: smooth-silhouette volumes of every mesh that is an oriented 2-manifold (the others by "
                  "the robust chain, named in the output; docs/smooth-silhouettes.md); smooth-gpu: smooth's "
                  "volume built on the GPU every frame (gpu/smooth_silhouette_volume.h)")
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
  CLI::Option* method_option = cmd->get_option("--method");
  cmd->callback([options, method_option, &exit_code] {
    options->method_given = method_option->count() > 0;
    exit_code = run_render(*options);
  });
}

}  // namespace shadowcert::cli
