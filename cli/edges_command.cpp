#include "cli/edges_command.h"

#include <fmt/core.h>

#include <array>
#include <chrono>
#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cli/exit_code.h"
#include "cli/frame_timing_output.h"
#include "cli/option_values.h"
#include "cli/wall_clock.h"
#include "core/eye_frame.h"
#include "core/input_error.h"
#include "gpu/edge_map.h"
#include "gpu/edge_style.h"
#include "gpu/egl_context.h"
#include "gpu/offscreen_target.h"
#include "gpu/png_image.h"
#include "gpu/shadow_method_renderer.h"
#include "io/output_file.h"
#include "io/scene_input.h"
#include "pipeline/mesh_palette.h"
#include "pipeline/method_inputs.h"
#include "pipeline/scene_smoothies.h"
#include "pipeline/silhouette_volumes.h"
#include "pipeline/stencil_choice.h"
#include "scene/merged_soup.h"

namespace shadowcert::cli {
namespace {

struct EdgesOptions {
  std::string input;
  std::string filter = "diagonal";
  std::optional<double> threshold;  // the profile threshold; default: the filter's answer to kDefaultEdgeDepthStep
  std::string style = "edges";
  std::string shadows;  // a render method; empty: no shadows
  double crease_angle = gpu::kDefaultEdgeCreaseAngleDegrees;
  std::string size;  // "WxH"; empty: the scene camera's
  std::string out;
  std::string edge_map;
  std::string json_file;
  bool timing = false;
  std::size_t frames = kDefaultTimingFrames;
  std::optional<int> device;
};


struct ValidatedEdgesOptions {
  gpu::EdgeFilter filter;
  gpu::EdgeStyle style;
  std::optional<gpu::ShadowMethod> shadows;
  double profile_threshold;
  double inner_threshold;
};

// The checks that need no input file (CLI11 checked the filter and style names already; they
// are checked again so that a caller without those checks gets the same message).
ValidatedEdgesOptions validate(const EdgesOptions& options) {
  const std::optional<gpu::EdgeFilter> filter = gpu::parse_edge_filter(options.filter);
  if (!filter) throw CLI::ValidationError("--filter", "unknown filter '" + options.filter + "': use diagonal, c1 or sobel");
  const std::optional<gpu::EdgeStyle> style = gpu::parse_edge_style(options.style);
  if (!style) throw CLI::ValidationError("--style", "unknown style '" + options.style + "': use edges, gooch or toon");
  if (options.threshold && !(*options.threshold >= 0.0 && *options.threshold <= 1.0))
    throw CLI::ValidationError("--threshold", fmt::format("must be in [0, 1] (an edge intensity), got {}", *options.threshold));
  if (!(options.crease_angle >= 0.0 && options.crease_angle <= 180.0))
    throw CLI::ValidationError("--crease-angle",
                               fmt::format("must be in [0, 180] degrees (between two faces' normals), got {}",
                                           options.crease_angle));
  ValidatedEdgesOptions v{*filter, *style, std::nullopt, 0.0, 0.0};
  if (!options.shadows.empty()) v.shadows = shadow_method_option(options.shadows, "--shadows");
  v.profile_threshold = options.threshold.value_or(gpu::profile_threshold(*filter, gpu::kDefaultEdgeDepthStep));
  v.inner_threshold = gpu::inner_threshold(*filter, options.crease_angle);
  return v;
}

// --edge-map: R = round(255 * profile), G = round(255 * inner), B = 0, A = 255.
gpu::RgbaImage edge_map_picture(const gpu::EdgeMapImage& map) {
  gpu::RgbaImage image(map.width, map.height);
  const auto byte = [](float v) { return static_cast<std::uint8_t>(std::lround(255.0f * std::clamp(v, 0.0f, 1.0f))); };
  for (std::size_t i = 0; i < map.profile.size(); ++i) {
    image.pixels[4 * i] = byte(map.profile[i]);
    image.pixels[4 * i + 1] = byte(map.inner[i]);
    image.pixels[4 * i + 3] = 255;
  }
  return image;
}

// What the shadow method's renderer reads (its GL objects live in the renderer, made after the
// context and destroyed before it).
struct ShadowFrameSource {
  MethodInputs inputs;
  std::optional<SilhouetteVolumes> silhouette;
};

// Prepares `method` as `render --method METHOD` does with its defaults (z-fail, exact signs, the
// default shadow-map size, pcf 3 x 3, pcss's default radius, world-space smoothies, the
// smooth-silhouette methods' default epsilon and crease angle).
void prepare_shadows(ShadowFrameSource& source, gpu::ShadowMethod method, const Scene& scene, const Soup& merged) {
  const Soup casters = merged_casters(scene);
  const std::array methods{method};
  source.inputs = prepare_method_inputs(casters, scene.lights, methods);
  if (gpu::is_silhouette_method(method)) {
    SilhouetteOptions silhouette_options;
    silhouette_options.near_plane = scene.camera.near_plane;  // the scene is in the eye's frame
    source.silhouette = silhouette_volumes(scene.meshes, scene.lights, method, silhouette_options);
    source.inputs.cpu_volumes = source.silhouette->per_light;
    source.inputs.smooth_casters = source.silhouette->gpu_casters;
  }
  const gpu::SceneBounds bounds = gpu::soup_bounds(merged);
  if (method == gpu::ShadowMethod::smoothie) add_smoothies(source.inputs, scene.lights, bounds);
}

int run_edges(const EdgesOptions& options) {
  const auto start = Clock::now();
  const ValidatedEdgesOptions v = validate(options);
  Scene scene = load_image_scene(options.input);
  if (scene.lights.empty()) throw InputError(options.input, "the scene has no light (the styles are shaded by the first)");
  apply_image_size(options.size, scene.camera);
  // GL is given the scene in its eye's frame (core/eye_frame.h), as render gives it.
  scene = eye_relative_scene(scene);
  const Soup merged = merged_soup(scene);
  if (merged.triangles.empty()) throw InputError(options.input, "no triangle to draw");

  // The scene's parts as GL draws them, shared by the shadow frame and the edge map.
  const std::vector<gpu::ShadedSoupPart> parts = shaded_parts(scene);
  ShadowFrameSource shadow_source;
  if (v.shadows) prepare_shadows(shadow_source, *v.shadows, scene, merged);

  const gpu::EglContext context = gpu::open_gl_context("edges", options.device);
  const Camera& camera = scene.camera;
  const gpu::OffscreenTarget target(camera.width, camera.height);
  gpu::EdgeMapRenderer edges(parts);
  gpu::EdgeStyleRenderer style;
  const gpu::DepthRange range = edges.depth_range(camera);

  // 1. The shadow frame (any render method), drawn first into the target: the edge map beside
  //    it never touches its framebuffer (gpu/edge_style.h).
  gpu::StencilShadowFrame frame;
  std::optional<gpu::ShadowMethodRenderer> shadow_renderer;
  if (v.shadows) {
    gpu::ShadowMethodOptions method_options;
    method_options.light_radius =
        *v.shadows == gpu::ShadowMethod::pcss ? gpu::default_light_radius(gpu::soup_bounds(merged)) : 0.0;
    shadow_renderer.emplace(*v.shadows, method_scene(shadow_source.inputs, parts, scene.lights),
                            method_options);
    frame = shadow_renderer->render(target, camera);
    try {
      shadow_renderer->check_capacity();
    } catch (const gpu::VolumeCapacityError& e) {
      fmt::print(stderr, "shadowcert edges: {}: {}; nothing written\n", options.input, e.what());
      return kExitCheckFailed;
    }
  }

  // 2. The edge map, 3. the style over it.
  const gpu::EdgeMapImage map = edges.render(target, camera, v.filter);
  const gpu::EdgePixelCounts counts = gpu::count_edge_pixels(map, v.profile_threshold, v.inner_threshold);
  if (counts.covered == 0)
    throw InputError(options.input, fmt::format("the camera sees nothing of the scene: no pixel of the {}x{} image is "
                                                "covered (check the camera's eye, target and field of view)",
                                                camera.width, camera.height));
  gpu::EdgeStyleOptions style_options;
  style_options.profile_threshold = v.profile_threshold;
  style_options.inner_threshold = v.inner_threshold;
  style_options.light = scene.lights.front();
  if (v.shadows) style_options.light_amount = frame.first_light;
  const gpu::RgbaImage image = style.render(target, edges, camera, v.style, style_options);

  // Per-pass times: always over a few frames; with --timing over --frames, printed as a table.
  const gpu::StageSync sync = context.software() ? gpu::StageSync::finish : gpu::StageSync::none;
  const std::size_t timed_frames = options.timing ? options.frames : kPlainTimedFrames;
  const gpu::FrameTiming timing = gpu::time_edge_frames(edges, style, target, camera, v.filter, v.style, style_options,
                                                        kTimingWarmUpFrames, timed_frames, sync);
  // On a software renderer the stage's wall time (bounded by glFinish) is its cost; on a GPU
  // its GL_TIME_ELAPSED (gpu/gpu_stage_timer.h).
  const auto pass_ms = [&](gpu::RenderStage stage) {
    return sync == gpu::StageSync::finish ? timing.wall(stage).median_ms : timing.gpu(stage).median_ms;
  };

  for (const std::string& file : {options.out, options.edge_map}) create_parent_directories(file);
  if (!options.out.empty()) gpu::write_png(options.out, image);
  if (!options.edge_map.empty()) gpu::write_png(options.edge_map, edge_map_picture(map));
  const double seconds = seconds_since(start);

  const std::string shadows_text = v.shadows ? fmt::format(", shadows by {}", gpu::shadow_method_name(*v.shadows)) : "";
  fmt::print("{}: {} triangles, {}x{}, {} filter, {} style{} on {}\n", options.input, merged.triangles.size(),
             camera.width, camera.height, gpu::edge_filter_name(v.filter), gpu::edge_style_name(v.style), shadows_text,
             context.renderer());
  fmt::print("  depth range {:.6g} to {:.6g} (view depth, fitted to the scene's bounds)\n", range.near, range.far);
  fmt::print("  thresholds: profile {:.6g}, inner {:.6g} (crease angle {} degrees)\n", v.profile_threshold,
             v.inner_threshold, options.crease_angle);
  fmt::print("  edge pixels: {} profile, {} inner, of {} covered\n", counts.profile, counts.inner, counts.covered);
  fmt::print("  ms per pass (median of {} frames): g_buffer {:.3f}, edge_filter {:.3f}, composite {:.3f}; frame {:.3f}\n",
             timing.frames, pass_ms(gpu::RenderStage::g_buffer), pass_ms(gpu::RenderStage::edge_filter),
             pass_ms(gpu::RenderStage::composite), timing.frame_cpu.median_ms);
  if (options.timing) print_frame_timing(timing, kTimingWarmUpFrames);

  if (!options.json_file.empty()) {
    nlohmann::json report{
        {"input", options.input},
        {"size", {camera.width, camera.height}},
        {"renderer", context.renderer()},
        {"device", context.device()},
        {"filter", gpu::edge_filter_name(v.filter)},
        {"style", gpu::edge_style_name(v.style)},
        {"shadows", v.shadows ? nlohmann::json(gpu::shadow_method_name(*v.shadows)) : nlohmann::json(nullptr)},
        {"crease_angle", options.crease_angle},
        {"thresholds", {{"profile", v.profile_threshold}, {"inner", v.inner_threshold}}},
        {"depth_range", {{"near", range.near}, {"far", range.far}}},
        {"edge_pixels", {{"profile", counts.profile}, {"inner", counts.inner}, {"covered", counts.covered}}},
        {"pass_ms",
         {{"g_buffer", pass_ms(gpu::RenderStage::g_buffer)},
          {"edge_filter", pass_ms(gpu::RenderStage::edge_filter)},
          {"composite", pass_ms(gpu::RenderStage::composite)},
          {"frame", timing.frame_cpu.median_ms},
          {"frames", timing.frames},
          {"source", sync == gpu::StageSync::finish ? "cpu wall (stages bounded by glFinish)" : "gpu queries"}}},
        {"seconds", seconds}};
    if (v.shadows) {
      std::uint64_t shadowed = 0;
      for (const float amount : frame.first_light) shadowed += amount >= 0.0f && amount < 1.0f ? 1 : 0;
      report["shadowed_pixels"] = shadowed;
    }
    // SCORES: the exact ground truth's precision, recall and F1 per class (pipeline/, the
    // ground-truth work; docs/edge-maps.md "Scores") go here, as report["scores"], once that
    // function exists: it takes `map` (gpu::EdgeMapImage), the thresholds above and the scene
    // as GL drew it (`scene`, in the eye's frame).
    if (options.timing) report["timing"] = frame_timing_json(timing, kTimingWarmUpFrames);
    write_json_file(options.json_file, report);
  }
  return kExitOk;
}

}  // namespace

void add_edges_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<EdgesOptions>();
  CLI::App* cmd = app.add_subcommand(
      "edges",
      "Edge maps (Nienhaus & Doellner 2003; docs/edge-maps.md): a G-buffer of eye-space normals and linear depth, "
      "an image-space filter giving profile (depth) and inner (normal) edge intensities, and a style drawn from "
      "them, optionally with the shadows of any render method");
  cmd->add_option("input", options->input, kImageInputHelp)->required();
  cmd->add_option("--filter", options->filter,
                  "diagonal (the paper's: the pairs A-H and C-F), c1 (the C1-discontinuity operator over the 3 x 3 "
                  "neighbourhood) or sobel (the baseline)")
      ->check(CLI::IsMember({"diagonal", "c1", "sobel"}))
      ->capture_default_str();
  cmd->add_option("--threshold", options->threshold,
                  "Profile edge threshold, an intensity in [0, 1]: a pixel is a profile edge above it (default: the "
                  "filter's answer to a depth step of 2% of the fitted depth range)");
  cmd->add_option("--style", options->style,
                  "edges (white paper, grey inner and black profile edges), gooch (technical illustration: inner "
                  "edges white, profile black) or toon (Lake's shade bands, anti-aliased, black edges)")
      ->check(CLI::IsMember({"edges", "gooch", "toon"}))
      ->capture_default_str();
  cmd->add_option("--shadows", options->shadows,
                  "Shade the style with the first light's shadows by this render method (cpu, cs, gs, ts, pertri, "
                  "shadowmap, pcf, pcss, smoothie, discrete, accurate, smooth, smooth-gpu), each with render's "
                  "defaults; the edge map is the same with and without");
  cmd->add_option("--crease-angle", options->crease_angle,
                  "Inner edge threshold as a dihedral angle in [0, 180] degrees (between the two faces' normals): "
                  "the filter's answer to a crease of that angle (docs/edge-maps.md)")
      ->capture_default_str();
  cmd->add_option("--size", options->size, "Image size WxH (default: the scene camera's)");
  cmd->add_option("--out", options->out, "Write the styled image (RGBA PNG, opaque)");
  cmd->add_option("--edge-map", options->edge_map,
                  "Write the edge intensities as one RGBA PNG: red = 255 x profile, green = 255 x inner");
  cmd->add_option("--json", options->json_file,
                  "Write options, thresholds, edge-pixel counts per class and ms per pass as JSON");
  CLI::Option* timing = cmd->add_flag(
      "--timing", options->timing,
      "Time each pass (g_buffer, edge_filter, composite) and each frame over --frames frames after 2 warm-up; "
      "print median, min and max and add them to --json under \"timing\"");
  cmd->add_option("--frames", options->frames, "--timing: how many frames to time")
      ->check(CLI::Range(std::size_t{1}, std::size_t{100000}))
      ->needs(timing)
      ->capture_default_str();
  cmd->add_option("--device", options->device, "Use EGL device N (default: a hardware device, else llvmpipe)");
  cmd->callback([options, &exit_code] { exit_code = run_edges(*options); });
}

}  // namespace shadowcert::cli
