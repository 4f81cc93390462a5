#include "cli/diff_command.h"

#include <fmt/core.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cli/comparison_json.h"
#include "cli/diff_report.h"
#include "cli/edge_map_output.h"
#include "cli/exit_code.h"
#include "cli/frame_timing_output.h"
#include "cli/light_image_output.h"
#include "cli/option_values.h"
#include "cli/silhouette_output.h"
#include "cli/stencil_output.h"
#include "io/output_file.h"
#include "pipeline/analytic_comparison.h"
#include "pipeline/comparison_pictures.h"
#include "pipeline/ray_traced_comparison.h"
#include "pipeline/scene_comparison.h"
#include "pipeline/soft_shadow_pictures.h"
#include "io/scene_input.h"
#include "core/input_error.h"
#include "reference/analytic_shadow_image.h"
#include "reference/exact_image.h"
#include "reference/pixel_comparison.h"
#include "gpu/egl_context.h"
#include "gpu/png_image.h"
#include "gpu/shadow_method_renderer.h"
#include "scene/merged_soup.h"

namespace shadowcert::cli {
namespace {


struct DiffOptions {
  std::string input;
  std::string methods;  // comma-separated; empty: every method
  std::string sign = "exact";  // --sign exact|float (gpu/sign_mode.h)
  std::string stencil;  // --stencil auto|zpass|zfail; empty: not given (the aliases, else zfail)
  bool zpass = false;
  bool zfail = false;
  std::string size;
  std::string out;
  std::string json_file;
  std::string report;
  unsigned threads = 0;  // --threads: the exact image's, the soft reference's and the ray tracer's; 0: every core
  std::optional<int> device;
  long long shadowmap_size = gpu::kDefaultShadowMapSize;
  SilhouetteOptions silhouette;  // --epsilon, --crease-angle
  // The soft shadow-map methods' parameters (docs/smoothies.md), as render takes them.
  std::optional<long long> pcf;             // pcf: K
  std::optional<double> light_radius;       // pcss: R
  std::optional<double> light_angle;        // pcss: a directional light's angular radius, degrees
  std::optional<double> smoothie_width;     // smoothie: D
  std::string smoothie_space = "world";     // smoothie: world | light
  // --soft: every light's exact soft reference, every method's light image against it
  // (docs/smoothies.md#the-error-table), with --samples K (a perfect square) and --light-radius.
  bool soft = false;
  long long samples = 64;
  // --edges: every filter's GL edge map against the exact edge ground truth (docs/edge-maps.md#scores).
  bool edges = false;
};

// The method's lit mask, gated by coverage (the frame's alpha).
gpu::GrayImage gl_mask(const gpu::StencilShadowFrame& frame) {
  gpu::GrayImage mask(frame.first_lit_mask.width, frame.first_lit_mask.height);
  for (std::size_t p = 0; p < mask.pixels.size(); ++p)
    mask.pixels[p] = frame.colour.pixels[4 * p + 3] != 0 && frame.first_lit_mask.pixels[p] != 0 ? 255 : 0;
  return mask;
}

gpu::GrayImage exact_mask(const ExactImage& image, std::size_t light) {
  gpu::GrayImage mask(image.width, image.height);
  mask.pixels = image.lights[light].lit;
  return mask;
}

// n(P) modulo 256, as the stencil holds it (no hit and undefined counts: 0).
gpu::GrayImage exact_counts(const ExactImage& image, std::size_t light) {
  gpu::GrayImage counts(image.width, image.height);
  const std::vector<std::uint32_t>& n = image.lights[light].counts;
  for (std::size_t p = 0; p < n.size(); ++p)
    counts.pixels[p] = n[p] == kNoHit || n[p] == kUndefinedCount ? 0 : static_cast<std::uint8_t>(n[p] % 256);
  return counts;
}

gpu::GrayImage ambiguity_image(const ExactImage& image, std::size_t light) {
  gpu::GrayImage out(image.width, image.height);
  for (std::size_t p = 0; p < out.pixels.size(); ++p) out.pixels[p] = image.lights[light].ambiguity[p] != 0 ? 255 : 0;
  return out;
}

// Hard errors red, ambiguous pixels tinted yellow, over the rendered frame (made opaque).
gpu::RgbaImage overlay(const gpu::RgbaImage& colour, const PixelComparison& comparison) {
  return error_overlay(colour, comparison);
}

// The report's "stencil" fact: the choice, and in auto mode each light's method.
std::string stencil_facts(StencilChoice choice, const SceneComparison& comparison) {
  if (choice != StencilChoice::automatic) return choice == StencilChoice::zpass ? "z-pass" : "z-fail";
  std::string text(stencil_choice_name(choice));
  for (std::size_t k = 0; k < comparison.stencil.size(); ++k)
    text += fmt::format("{} light {}: {}", k == 0 ? ";" : ",", k,
                        describe_stencil(comparison.stencil[k]));
  return text;
}

// "" for a single light, "_light<k>" with several: the output files' suffix.
std::string light_suffix(std::size_t light, std::size_t lights) {
  return lights > 1 ? fmt::format("_light{}", light) : std::string();
}

nlohmann::json comparison_json(const PixelComparison& c) {
  return {{"hard_errors", c.hard_errors},   {"ambiguous", c.ambiguous},   {"agree", c.agree},
          {"coverage_errors", c.coverage_errors}, {"lit_errors", c.lit_errors}, {"count_errors", c.count_errors}};
}

// The soft reference's own figures, per light.
nlohmann::json soft_reference_json(const SoftReference& r) {
  std::array<std::uint64_t, 5> regions{};
  for (std::size_t p = 0; p < r.image.pixels(); ++p) ++regions[static_cast<std::size_t>(r.image.region(p))];
  return {{"samples", r.image.samples.size()},
          {"seconds", r.image.stats.seconds + r.contact_seconds},
          {"umbra", regions[static_cast<std::size_t>(SoftRegion::umbra)]},
          {"penumbra", regions[static_cast<std::size_t>(SoftRegion::penumbra)]},
          {"lit", regions[static_cast<std::size_t>(SoftRegion::lit)]},
          {"undefined", regions[static_cast<std::size_t>(SoftRegion::undefined)]},
          {"contact", std::count(r.contact.begin(), r.contact.end(), std::uint8_t{1})}};
}

// One line of the soft table; `ref noise` is the reference's own (SoftShadowErrors::reference_noise):
// mean errors that differ by less are within the estimator's noise.
std::string soft_line(const SoftShadowErrors& e) {
  return fmt::format("{:9.4f} {:7.3f} {:8.4f} {:8.4f} {:8.4f} {:>11} {:>12} {:+9.4f} {:>9}", e.mean_error,
                     e.max_error, e.umbra_mean_error, e.penumbra_mean_error, e.outside_penumbra_mean_error,
                     fmt::format("{}/{}", e.leaks, e.contact), fmt::format("{}/{}", e.acne, e.lit_facing),
                     e.mean_signed_error, fmt::format("±{:.4f}", e.reference_noise));
}

// The soft reference's light, for the report and the text: a disk of the radius around a point
// light, of the angle about a directional one.
std::string soft_light_text(const Light& light, double radius, double angle_degrees) {
  return light.directional() ? fmt::format("sun of angular radius {:.4g} degrees", angle_degrees)
                             : fmt::format("disk light of radius {:.4g}", radius);
}

// The report's line for a method against the soft reference.
std::string soft_fact(const SoftShadowErrors& e) {
  return fmt::format("mean |error| {:.4f} (max {:.3f}, signed {:+.4f}); umbra {:.4f}, penumbra {:.4f}, outside the "
                     "penumbra {:.4f}; leaks {} of {} contact pixels, acne {} of {} lit pixels; the reference's "
                     "noise ±{:.4f} (a pixel's 95% half-width {:.3f})",
                     e.mean_error, e.max_error, e.mean_signed_error, e.umbra_mean_error, e.penumbra_mean_error,
                     e.outside_penumbra_mean_error, e.leaks, e.contact, e.acne, e.lit_facing, e.reference_noise,
                     e.reference_ci95);
}

// The analytic truth's own figures: its time, the meshes cast as ellipsoids, its band, and per
// light how many pixels it puts in each class.
nlohmann::json analytic_truth_json(const AnalyticShadowImage& truth, const Scene& scene) {
  nlohmann::json casters = nlohmann::json::array();
  for (std::uint32_t m : truth.analytic_casters) casters.push_back(scene.meshes[m].name);
  nlohmann::json per_light = nlohmann::json::array();
  constexpr std::array<std::pair<AnalyticPixel, const char*>, 7> kClasses{
      {{AnalyticPixel::lit, "lit"},
       {AnalyticPixel::shadowed, "shadowed"},
       {AnalyticPixel::ambiguous, "ambiguous"},
       {AnalyticPixel::caster_lit, "caster_lit"},
       {AnalyticPixel::caster_shadowed, "caster_shadowed"},
       {AnalyticPixel::caster_band, "caster_band"},
       {AnalyticPixel::caster_ambiguous, "caster_ambiguous"}}};
  for (const std::vector<AnalyticPixel>& light : truth.lights) {
    nlohmann::json counts = nlohmann::json::object();
    for (const auto& [value, name] : kClasses) counts[name] = std::count(light.begin(), light.end(), value);
    per_light.push_back(counts);
  }
  return {{"seconds", truth.seconds},
          {"casters", casters},
          {"terminator_band", kDefaultTerminatorBand},
          {"pixels", per_light}};
}

nlohmann::json method_json(const MethodRun& run, const DiffOptions& options) {
  nlohmann::json j{{"robust", run.held_robust},
                   {"hard_errors", run.sum(&PixelComparison::hard_errors)},
                   {"ambiguous", run.sum(&PixelComparison::ambiguous)},
                   {"agree", run.sum(&PixelComparison::agree)},
                   {"coverage_errors", run.sum(&PixelComparison::coverage_errors)},
                   {"lit_errors", run.sum(&PixelComparison::lit_errors)},
                   {"count_errors", run.sum(&PixelComparison::count_errors)},
                   {"closed", nullptr},
                   {"gl_ms", run.gl_ms()},
                   {"failed", run.failed()}};
  if (const std::optional<bool> closed = run.closed()) j["closed"] = *closed;
  if (gpu::uses_shadow_map(run.method)) j["shadow_map_size"] = options.shadowmap_size;
  if (run.method == gpu::ShadowMethod::pcf) j["pcf_kernel"] = options.pcf.value_or(gpu::kDefaultPcfKernel);
  nlohmann::json per_light = nlohmann::json::array();
  for (const LightRun& l : run.lights) {
    nlohmann::json lj = comparison_json(l.comparison);
    lj["gl_ms"] = l.gl_ms;
    if (l.closure) {
      lj["closed"] = l.closure->closed;
      lj["unbalanced_edges"] = l.closure->unbalanced.size();
      lj["volume_triangles"] = l.volume_triangles;
    }
    if (!l.capacity_error.empty()) lj["capacity_error"] = l.capacity_error;
    if (l.analytic) lj["analytic"] = analytic_counts_json(*l.analytic);
    if (l.soft) lj["soft"] = soft_errors_json(*l.soft);
    per_light.push_back(lj);
  }
  j["per_light"] = per_light;
  if (const std::optional<AnalyticCounts> a = run.analytic()) j["analytic"] = analytic_counts_json(*a);
  return j;
}

// A ray-traced run's summary: diff's figures and its own times (docs/ray-tracing.md).
nlohmann::json ray_traced_json(const RayTracedRun& run) {
  nlohmann::json j{{"robust", false},
                   {"ray_traced", true},
                   {"mode", raytrace::build_mode_name(ray_traced_entry(run.method).mode)},
                   {"hard_errors", run.sum(&PixelComparison::hard_errors)},
                   {"ambiguous", run.sum(&PixelComparison::ambiguous)},
                   {"agree", run.sum(&PixelComparison::agree)},
                   {"coverage_errors", run.sum(&PixelComparison::coverage_errors)},
                   {"lit_errors", run.sum(&PixelComparison::lit_errors)},
                   {"count_errors", run.sum(&PixelComparison::count_errors)},
                   {"closed", nullptr},
                   {"gl_ms", run.ms()},
                   {"build_seconds", run.build_seconds},
                   {"trace_seconds", run.trace_seconds},
                   {"failed", false}};
  nlohmann::json per_light = nlohmann::json::array();
  for (const LightRun& l : run.lights) {
    nlohmann::json lj = comparison_json(l.comparison);
    if (l.soft) lj["soft"] = soft_errors_json(*l.soft);
    per_light.push_back(lj);
  }
  j["per_light"] = per_light;
  if (!run.lights.empty() && run.lights.front().soft)
    j["soft_seconds"] = {{"build", run.soft_build_seconds}, {"trace", run.soft_trace_seconds}};
  return j;
}

// Every run of the comparison as the pictures and tables show it: the GL runs, then the
// ray-traced ones (pipeline/ray_traced_comparison.h), each with its name and per-light frames.
struct RunView {
  std::string name;
  const std::vector<LightRun>* lights = nullptr;
  bool held_robust = false;
  bool failed = false;
  std::optional<bool> closed;
  double ms = 0.0;    // GL: mean ms per frame summed over lights; rt: build and trace
  std::string note;   // after the figures: "  FAILED", "  (baseline)", ...
  std::string parameters;  // the report's parameter cell
};

std::vector<RunView> run_views(const SceneComparison& comparison, const DiffOptions& options) {
  std::vector<RunView> views;
  for (const MethodRun& run : comparison.runs)
    views.push_back({std::string(gpu::shadow_method_name(run.method)), &run.lights, run.held_robust, run.failed(),
                     run.closed(), run.gl_ms(),
                     run.failed()                          ? "  FAILED"
                     : run.held_robust                     ? ""
                     : gpu::uses_shadow_map(run.method)    ? "  (baseline)"
                                                           : "  (smooth surface: its error)",
                     gpu::uses_shadow_map(run.method) ? fmt::format("{0}x{0} depth map", options.shadowmap_size)
                                                      : std::string()});
  for (const RayTracedRun& run : comparison.ray_traced)
    views.push_back({std::string(ray_traced_method_name(run.method)), &run.lights, false, false, std::nullopt, run.ms(),
                     fmt::format("  (float peer; build {:.1f} ms, trace {:.1f} ms)", 1000.0 * run.build_seconds,
                                 1000.0 * run.trace_seconds),
                     fmt::format("Embree {} mode, CPU: build {:.1f} ms, trace {:.1f} ms",
                                 raytrace::build_mode_name(ray_traced_entry(run.method).mode),
                                 1000.0 * run.build_seconds, 1000.0 * run.trace_seconds)});
  return views;
}

// The silhouette runs against the analytic shadow, one line each (reported, never a failure).
void print_analytic(const AnalyticShadowImage& truth, const Scene& scene, const std::vector<MethodRun>& runs) {
  std::string casters;
  for (std::uint32_t m : truth.analytic_casters) casters += (casters.empty() ? "" : ", ") + scene.meshes[m].name;
  fmt::print("  analytic shadow of {} as ellipsoid{}: {:.2f} s; pixels against it (never a failure):\n", casters,
             truth.analytic_casters.size() == 1 ? "" : "s", truth.seconds);
  fmt::print("  {:<10} {:>10} {:>10} {:>10} {:>10} {:>10} {:>10} {:>10}\n", "method", "recv agree", "disagree",
             "ambiguous", "self agree", "disagree", "band", "ambiguous");
  for (const MethodRun& run : runs)
    if (const std::optional<AnalyticCounts> a = run.analytic())
      fmt::print("  {:<10} {:>10} {:>10} {:>10} {:>10} {:>10} {:>10} {:>10}\n", gpu::shadow_method_name(run.method),
                 a->receiver_agree, a->receiver_disagree, a->receiver_ambiguous, a->caster_agree, a->caster_disagree,
                 a->caster_band, a->caster_ambiguous);
}

// The report's line for a silhouette run against the analytic shadow.
std::string analytic_fact(const AnalyticCounts& a) {
  return fmt::format("receivers: {} of {} decided pixels disagree ({} ambiguous); the casters' own pixels: {} of {} "
                     "disagree with the interpolated-normal terminator ({} in its band, {} ambiguous)",
                     a.receiver_disagree, a.receiver_agree + a.receiver_disagree, a.receiver_ambiguous,
                     a.caster_disagree, a.caster_agree + a.caster_disagree, a.caster_band, a.caster_ambiguous);
}

// ---- the command: one scene compared, step by step ----------------------------------------------

// Step 1: what the options ask for, checked before any file is read.
struct DiffRequest {
  MethodSelection methods;
  StencilChoice stencil_choice = StencilChoice::zfail;
};

DiffRequest validate_diff(const DiffOptions& options) {
  const MethodSelection methods = method_selection_option(options.methods, "--methods");
  const StencilChoice stencil_choice = stencil_option(options.stencil, options.zpass, options.zfail);
  if (options.shadowmap_size < 1 || options.shadowmap_size > gpu::kMaxShadowMapSize)
    throw CLI::ValidationError("--shadowmap-size", fmt::format("must be in [1, {}], got {}", gpu::kMaxShadowMapSize,
                                                               options.shadowmap_size));
  if (options.pcf && (*options.pcf < 1 || *options.pcf > gpu::kMaxPcfKernel || *options.pcf % 2 == 0))
    throw CLI::ValidationError("--pcf", fmt::format("K must be odd and in [1, {}], got {}", gpu::kMaxPcfKernel,
                                                    *options.pcf));
  if (options.light_radius && (!std::isfinite(*options.light_radius) || !(*options.light_radius > 0.0)))
    throw CLI::ValidationError("--light-radius",
                               fmt::format("must be finite and > 0 (world units), got {}", *options.light_radius));
  if (options.light_angle) check_light_angle(*options.light_angle);
  if (options.samples < 1 || options.samples > 65536 ||
      [&] {
        const auto root = static_cast<long long>(std::llround(std::sqrt(static_cast<double>(options.samples))));
        return root * root != options.samples;
      }())
    throw CLI::ValidationError("--samples", fmt::format("must be a perfect square in [1, 65536] (64 = 8 x 8 strata), "
                                                        "got {}", options.samples));
  if (options.smoothie_width && (!std::isfinite(*options.smoothie_width) || !(*options.smoothie_width > 0.0)))
    throw CLI::ValidationError("--smoothie-width",
                               fmt::format("must be finite and > 0 (world units), got {}", *options.smoothie_width));
  return {methods, stencil_choice};
}

// Step 2: the scene, sized; its triangle count (every mesh's).
struct DiffScene {
  Scene scene;
  std::size_t triangles = 0;
};

DiffScene load_diff_scene(const DiffOptions& options) {
  Scene scene = load_image_scene(options.input);
  if (scene.lights.empty()) throw InputError(options.input, "the scene has no light");
  apply_image_size(options.size, scene.camera);
  const std::size_t triangles = merged_soup(scene).triangles.size();
  if (triangles == 0) throw InputError(options.input, "no triangle to render");
  return {std::move(scene), triangles};
}

// Step 3: the comparison's options (pipeline/scene_comparison.h) from the command's.
SceneComparisonOptions comparison_options_of(const DiffRequest& request, const DiffOptions& options) {
  const StencilChoice stencil_choice = request.stencil_choice;
  SceneComparisonOptions comparison_options;
  comparison_options.method_options.stencil =
      stencil_choice == StencilChoice::zpass ? gpu::StencilMethod::zpass : gpu::StencilMethod::zfail;
  comparison_options.stencil_auto = stencil_choice == StencilChoice::automatic;
  comparison_options.method_options.shadow_map_size = static_cast<std::uint32_t>(options.shadowmap_size);
  comparison_options.method_options.sign = *gpu::parse_sign_mode(options.sign);  // CLI11 checked the name
  comparison_options.timed_frames = kPlainTimedFrames;
  comparison_options.silhouette = options.silhouette;
  comparison_options.method_options.pcf_kernel = static_cast<std::uint32_t>(options.pcf.value_or(gpu::kDefaultPcfKernel));
  comparison_options.method_options.light_radius = options.light_radius.value_or(0.0);  // 0: the default
  comparison_options.method_options.light_angle_degrees = options.light_angle.value_or(0.0);  // likewise
  comparison_options.smoothie.width = options.smoothie_width.value_or(0.0);            // 0: the default
  comparison_options.smoothie.space = *parse_smoothie_space(options.smoothie_space);  // CLI11 checked it
  if (options.soft) {
    SoftReferenceOptions soft;
    soft.sampling.radius = options.light_radius.value_or(0.0);  // 0: the pcss default
    soft.sampling.samples = static_cast<std::uint32_t>(options.samples);
    soft.progress = isatty(fileno(stderr)) != 0;
    comparison_options.soft = soft;
  }
  comparison_options.ray_traced = request.methods.ray_traced;
  comparison_options.ray_traced_threads = options.threads;
  // A progress bar only on a terminal: logs and pipes get no carriage returns.
  comparison_options.progress = isatty(fileno(stderr)) != 0;
  return comparison_options;
}

// What steps 5 to 8 read: the comparison of step 4 and what it was made of.
struct DiffResult {
  const DiffOptions& options;
  const DiffRequest& request;
  const Scene& scene;
  std::size_t triangles;
  const gpu::EglContext* context;  // nullptr: no GL method and no --edges (no context opened)
  const SceneComparison& comparison;
  const EdgeMapComparisonOptions& edge_options;
  const std::optional<EdgeMapComparison>& edge_maps;
};

// The exact image's own pictures of light k: its mask, its counts (n mod 256) and its ambiguity.
std::vector<std::pair<std::string, gpu::GrayImage>> exact_images(const ExactImage& exact, std::size_t k) {
  const std::string s = light_suffix(k, exact.lights.size());
  return {{"exact_mask" + s, exact_mask(exact, k)},
          {"exact_counts" + s, exact_counts(exact, k)},
          {"exact_ambiguous" + s, ambiguity_image(exact, k)}};
}

// The top of the counts' colour scale: the largest defined count of any light.
std::uint32_t counts_top(const ExactImage& exact) {
  std::uint32_t top = 1;
  for (std::size_t k = 0; k < exact.lights.size(); ++k) top = std::max(top, max_count(exact, k));
  return top;
}

// Per light, the pixels the exact image calls ambiguous.
nlohmann::json ambiguous_pixels(const ExactImage& exact) {
  nlohmann::json ambiguous = nlohmann::json::array();
  for (const ExactLightImage& l : exact.lights)
    ambiguous.push_back(std::count_if(l.ambiguity.begin(), l.ambiguity.end(), [](std::uint8_t a) { return a != 0; }));
  return ambiguous;
}

// Step 5: --out's images: the exact masks and counts, and per method its mask and overlay.
void write_diff_images(const DiffResult& result) {
  const Scene& scene = result.scene;
  const DiffOptions& options = result.options;
  const SceneComparison& comparison = result.comparison;
  const ExactImage& exact = comparison.exact;
  const std::size_t light_count = scene.lights.size();
  const std::optional<EdgeMapComparison>& edge_maps = result.edge_maps;
  if (!options.out.empty()) {
    const std::filesystem::path dir(options.out);
    create_parent_directories(dir / "summary.json");
    if (edge_maps) write_edge_map_pictures(dir, *edge_maps);
    for (std::size_t k = 0; k < light_count; ++k) {
      for (const auto& [name, image] : exact_images(exact, k)) gpu::write_png((dir / (name + ".png")).string(), image);
      // The counts in a perceptual colour map: the gray file holds n mod 256, where 1 and 2 look black.
      gpu::write_png((dir / ("exact_counts_viridis" + light_suffix(k, light_count) + ".png")).string(),
                     count_colour_image(exact, k, counts_top(exact)));
      for (const RunView& run : run_views(comparison, options)) {
        const std::string& name = run.name;
        const LightRun& l = (*run.lights)[k];
        const std::string s = light_suffix(k, light_count);
        gpu::write_png((dir / (name + "_mask" + s + ".png")).string(), gl_mask(l.frame));
        gpu::write_png((dir / (name + "_overlay" + s + ".png")).string(), overlay(l.frame.colour, l.comparison));
        if (!comparison.soft.empty()) {
          gpu::write_png((dir / (name + "_soft_error" + s + ".png")).string(),
                         soft_error_image(comparison.soft[k].image, l.frame.first_light));
          write_light_image(dir / (name + "_light" + s + ".png"), scene.camera.width, scene.camera.height,
                            l.frame.first_light);
        }
      }
      if (!comparison.soft.empty()) {
        const SoftReference& r = comparison.soft[k];
        const std::string s = light_suffix(k, light_count);
        write_light_image(dir / ("soft_reference_light" + s + ".png"), r.image.width, r.image.height, r.image.light);
        gpu::write_png((dir / ("soft_reference_regions" + s + ".png")).string(), soft_region_image(r));
      }
    }
  }

}

// Step 6: the summary (--json, and summary.json in --out).
nlohmann::json diff_summary(const DiffResult& result) {
  const Scene& scene = result.scene;
  const DiffOptions& options = result.options;
  const SceneComparison& comparison = result.comparison;
  const ExactImage& exact = comparison.exact;
  const std::vector<MethodRun>& runs = comparison.runs;
  const std::size_t light_count = scene.lights.size();
  const std::optional<EdgeMapComparison>& edge_maps = result.edge_maps;
  nlohmann::json lit = nlohmann::json::array();
  for (const ExactLightImage& l : exact.lights)
    lit.push_back(std::count_if(l.lit.begin(), l.lit.end(), [](std::uint8_t a) { return a != 0; }));
  nlohmann::json summary{
      {"input", options.input},
      {"size", {scene.camera.width, scene.camera.height}},
      {"stencil", stencil_choice_name(result.request.stencil_choice)},
      {"stencil_per_light", stencil_json(comparison.stencil)},
      {"renderer", result.context ? result.context->renderer() : std::string()},
      {"device", result.context ? result.context->device() : std::string()},
      {"lights", light_count},
      {"triangles", result.triangles},
      // The TBB threads the exact image and the ray tracer ran on (--threads).
      {"threads", tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism)},
      {"exact_seconds", exact.stats.seconds},
      {"exact",
       {{"tree_seconds", exact.stats.tree_seconds},
        {"hit_seconds", exact.stats.hit_seconds},
        {"count_seconds", exact.stats.count_seconds},
        {"rays", exact.stats.rays},
        {"counts", exact.stats.counts},
        {"footprint_seconds", exact.stats.footprint_seconds},
        {"float_rounded_seconds", comparison.rounded_seconds},
        {"ambiguous_pixels", ambiguous_pixels(exact)},
        {"lit_pixels", lit},
        {"no_hit_pixels", std::count(exact.hit_triangles.begin(), exact.hit_triangles.end(), kNoHit)}}},
      {"methods", nlohmann::json::object()},
      {"passed", comparison.passed()}};
  for (const MethodRun& run : runs) summary["methods"][std::string(gpu::shadow_method_name(run.method))] = method_json(run, options);
  for (const RayTracedRun& run : comparison.ray_traced)
    summary["methods"][std::string(ray_traced_method_name(run.method))] = ray_traced_json(run);
  for (const SilhouetteVolumes& s : comparison.silhouettes)
    summary["methods"][std::string(gpu::shadow_method_name(s.method))]["casters"] = silhouette_casters_json(s);
  if (comparison.analytic) summary["analytic"] = analytic_truth_json(*comparison.analytic, scene);
  if (!comparison.soft.empty()) {
    nlohmann::json per_light = nlohmann::json::array();
    for (const SoftReference& r : comparison.soft) per_light.push_back(soft_reference_json(r));
    summary["soft_reference"] = {{"radius", comparison.soft_radius},
                                 {"angle_degrees", comparison.soft_angle_degrees},
                                 {"samples", options.samples},
                                 {"ci95", reference_half_width(static_cast<std::uint32_t>(options.samples))},
                                 {"per_light", per_light}};
  }
  if (edge_maps)
    summary["edge_maps"] = edge_maps_json(*edge_maps, result.edge_options.crease_degrees, result.edge_options.grazing_degrees);
  return summary;
}

// Step 7: --report's page.
void write_html_report(const DiffResult& result) {
  const Scene& scene = result.scene;
  const DiffOptions& options = result.options;
  const SceneComparison& comparison = result.comparison;
  const ExactImage& exact = comparison.exact;
  const std::vector<MethodRun>& runs = comparison.runs;
  const std::size_t light_count = scene.lights.size();
  const std::optional<EdgeMapComparison>& edge_maps = result.edge_maps;
  DiffReport report;
  report.title = "shadowcert diff: " + options.input;
  report.passed = comparison.passed();
  report.facts = {{"image", fmt::format("{}x{}, {} light(s), {} triangles", scene.camera.width, scene.camera.height,
                                        light_count, result.triangles)},
                  {"stencil", stencil_facts(result.request.stencil_choice, comparison)},
                  {"renderer", result.context ? result.context->renderer() : std::string("none (no GL method)")},
                  {"exact image", fmt::format("{:.2f} s (tree {:.2f}, hits {:.2f}, footprints {:.2f}, counts {:.2f}; "
                                              "{} rays, {} counts), and {:.2f} s for the float-rounded scene",
                                              exact.stats.seconds, exact.stats.tree_seconds, exact.stats.hit_seconds,
                                              exact.stats.footprint_seconds, exact.stats.count_seconds,
                                              exact.stats.rays, exact.stats.counts,
                                              comparison.rounded_seconds)}};
  for (const MethodRun& run : runs)
    if (const std::optional<AnalyticCounts> analytic = run.analytic())
      report.facts.emplace_back("analytic shadow, " + std::string(gpu::shadow_method_name(run.method)),
                                analytic_fact(*analytic));
  for (std::size_t k = 0; k < comparison.soft.size(); ++k) {
    const SoftReference& r = comparison.soft[k];
    report.facts.emplace_back(
        "soft reference" + (light_count > 1 ? fmt::format(", light {}", k) : std::string()),
        fmt::format("{}, {} samples (a pixel's 95% half-width {:.3f}), {:.2f} s; error images: method minus "
                    "reference, blue too dark, red too bright, green where coverage differs",
                    soft_light_text(scene.lights[k], comparison.soft_radius, comparison.soft_angle_degrees),
                    r.image.samples.size(), reference_half_width(static_cast<std::uint32_t>(r.image.samples.size())),
                    r.image.stats.seconds + r.contact_seconds));
    for (const RunView& run : run_views(comparison, options))
      if ((*run.lights)[k].soft)
        report.facts.emplace_back("soft error, " + run.name +
                                      (light_count > 1 ? fmt::format(", light {}", k) : std::string()),
                                  soft_fact(*(*run.lights)[k].soft));
  }
  const auto sum = [](const RunView& run, std::uint64_t PixelComparison::*figure) {
    std::uint64_t n = 0;
    for (const LightRun& l : *run.lights) n += l.comparison.*figure;
    return n;
  };
  for (const RunView& run : run_views(comparison, options))
    report.rows.push_back({run.name, run.held_robust, sum(run, &PixelComparison::hard_errors),
                           sum(run, &PixelComparison::ambiguous), sum(run, &PixelComparison::agree), run.closed,
                           run.ms, run.parameters});
  for (std::size_t k = 0; k < light_count; ++k) {
    const std::string s = light_count > 1 ? fmt::format(", light {}", k) : std::string();
    for (const auto& [name, image] : exact_images(exact, k)) {
      // The counts in viridis with a legend (n mod 256 in gray is all but black).
      if (name.rfind("exact_counts", 0) == 0) {
        report.exact_images.push_back(
            {name + " (viridis, legend below)" + s, gpu::encode_png(count_colour_image(exact, k, counts_top(exact)))});
        continue;
      }
      report.exact_images.push_back({name + s, gpu::encode_png(image)});
    }
    if (!comparison.soft.empty()) {
      const SoftReference& r = comparison.soft[k];
      report.exact_images.push_back(
          {"soft reference light" + s, gpu::encode_png(light_image_gray(r.image.width, r.image.height, r.image.light))});
      report.exact_images.push_back({"soft reference regions (umbra black, penumbra gray, contact red)" + s,
                                     gpu::encode_png(soft_region_image(r))});
      report.exact_images.push_back({"error colours: -1 (too dark) to +1 (too bright)",
                                     gpu::encode_png(diverging_colour_bar(256, 16))});
    }
    for (const RunView& run : run_views(comparison, options)) {
      const std::string& name = run.name;
      const LightRun& l = (*run.lights)[k];
      report.method_images.push_back(
          {name + s,
           {{name + " overlay" + s, gpu::encode_png(overlay(l.frame.colour, l.comparison))},
            {name + " lit mask" + s, gpu::encode_png(gl_mask(l.frame))},
            {"exact lit mask" + s, gpu::encode_png(exact_mask(exact, k))}}});
      if (!comparison.soft.empty()) {
        const gpu::StencilShadowFrame& f = l.frame;
        report.method_images.back().second.push_back(
            {name + " light" + s, gpu::encode_png(light_image_gray(scene.camera.width, scene.camera.height,
                                                                     f.first_light))});
        report.method_images.back().second.push_back(
            {name + " soft error" + s, gpu::encode_png(soft_error_image(comparison.soft[k].image, f.first_light))});
      }
    }
  }
  report.counts_legend = counts_legend(counts_top(exact));
  if (edge_maps) {
    for (auto& fact : edge_map_facts(*edge_maps)) report.facts.push_back(std::move(fact));
    report.method_images.push_back({"edge maps", edge_map_report_images(*edge_maps)});
  }
  write_diff_report(options.report, report);
}

// Step 8: the tables on stdout.
void print_diff(const DiffResult& result) {
  const Scene& scene = result.scene;
  const DiffOptions& options = result.options;
  const SceneComparison& comparison = result.comparison;
  const ExactImage& exact = comparison.exact;
  const std::vector<MethodRun>& runs = comparison.runs;
  const std::size_t light_count = scene.lights.size();
  const std::optional<EdgeMapComparison>& edge_maps = result.edge_maps;
  fmt::print("{}: {} triangles, {} light(s), {}x{}, {}\n", options.input, result.triangles, light_count,
             scene.camera.width, scene.camera.height,
             result.context ? fmt::format("{} on {}", stencil_choice_name(result.request.stencil_choice),
                                          result.context->renderer())
                            : std::string("ray-traced methods only (no GL context)"));
  print_stencil(comparison.stencil);
  for (const SilhouetteVolumes& s : comparison.silhouettes) print_silhouette_casters(s);
  fmt::print("  exact image: {:.2f} s (tree {:.2f}, hits {:.2f}, footprints {:.2f}, counts {:.2f}), float-rounded "
             "scene {:.2f} s; ambiguous pixels {}\n",
             exact.stats.seconds, exact.stats.tree_seconds, exact.stats.hit_seconds, exact.stats.footprint_seconds,
             exact.stats.count_seconds, comparison.rounded_seconds, ambiguous_pixels(exact).dump());
  fmt::print("  {:<10} {:>11} {:>10} {:>10} {:>7} {:>9}\n", "method", "hard errors", "ambiguous", "agree", "closed",
             "gl ms");
  for (const RunView& run : run_views(comparison, options)) {
    std::uint64_t hard = 0, ambiguous = 0, agree = 0;
    for (const LightRun& l : *run.lights) {
      hard += l.comparison.hard_errors;
      ambiguous += l.comparison.ambiguous;
      agree += l.comparison.agree;
    }
    fmt::print("  {:<10} {:>11} {:>10} {:>10} {:>7} {:>9.2f}{}\n", run.name, hard, ambiguous, agree,
               run.closed ? (*run.closed ? "yes" : "NO") : "-", run.ms, run.note);
  }
  if (comparison.analytic) print_analytic(*comparison.analytic, scene, runs);
  if (edge_maps) print_edge_maps(*edge_maps);
  for (std::size_t k = 0; k < comparison.soft.size(); ++k) {
    const SoftReference& r = comparison.soft[k];
    fmt::print("  soft reference{}: {}, {} samples (a pixel's 95% half-width {:.3f}), {:.2f} s; light against it "
               "(never a failure; ref noise: mean errors closer than it are within the reference's sampling):\n",
               light_count > 1 ? fmt::format(" of light {}", k) : std::string(),
               soft_light_text(scene.lights[k], comparison.soft_radius, comparison.soft_angle_degrees),
               r.image.samples.size(), reference_half_width(static_cast<std::uint32_t>(r.image.samples.size())),
               r.image.stats.seconds + r.contact_seconds);
    fmt::print("  {:<10} {:>9} {:>7} {:>8} {:>8} {:>8} {:>11} {:>12} {:>9} {:>9}\n", "method", "mean err", "max",
               "umbra", "penumbra", "outside", "leaks", "acne", "signed", "ref noise");
    for (const RunView& run : run_views(comparison, options))
      if ((*run.lights)[k].soft) fmt::print("  {:<10} {}\n", run.name, soft_line(*(*run.lights)[k].soft));
  }
  fmt::print("  {}\n", comparison.passed() ? "passed: no robust method has a hard error or an open volume"
                              : "FAILED: a robust method has a hard error or an open volume");
}

int run_diff(const DiffOptions& options) {
  const DiffRequest request = validate_diff(options);                       // 1. the options
  const std::unique_ptr<tbb::global_control> thread_cap = thread_limit(options.threads);
  const DiffScene d = load_diff_scene(options);                             // 2. the scene
  // A GL context only where something draws with GL: `--methods rt` runs on any machine.
  std::optional<gpu::EglContext> context;
  if (!request.methods.gl.empty() || options.edges) context.emplace(gpu::open_gl_context("diff", options.device));
  const SceneComparison comparison =                                        // 3, 4. exact image, GL, rt
      compare_scene(d.scene, request.methods.gl, comparison_options_of(request, options));
  // --edges: the edge maps' scores (reported, never a failure).
  const EdgeMapComparisonOptions edge_options;
  std::optional<EdgeMapComparison> edge_maps;
  if (options.edges) edge_maps = compare_edge_maps(d.scene, edge_options);
  const DiffResult r{options, request, d.scene, d.triangles, context ? &*context : nullptr, comparison, edge_options,
                     edge_maps};
  if (!options.out.empty()) write_diff_images(r);                           // 5. images
  const nlohmann::json summary = diff_summary(r);                           // 6. summary
  if (!options.out.empty()) write_json_file(std::filesystem::path(options.out) / "summary.json", summary);
  if (!options.json_file.empty()) write_json_file(options.json_file, summary);
  if (!options.report.empty()) write_html_report(r);                        // 7. report
  print_diff(r);                                                            // 8. tables
  return comparison.passed() ? kExitOk : kExitCheckFailed;
}

}  // namespace

void add_diff_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<DiffOptions>();
  CLI::App* cmd = app.add_subcommand(
      "diff",
      "Certify GL shadow methods against the exact image (docs/definitions.md#pixel-protocol): per method and light, hard errors, "
      "ambiguous and agreeing pixels, and the exact closure of each volume method's captured volume. Exit 1 "
      "when a robust method (cpu, cs, gs, ts, pertri, discrete) has a hard error or any volume is open");
  cmd->add_option("input", options->input, kImageInputHelp)->required();
  cmd->add_option("--methods", options->methods,
                  "Comma-separated methods to compare: cpu, cs, gs, ts, pertri, shadowmap, and the smooth-silhouette "
                  "methods discrete, accurate, smooth, smooth-gpu (docs/smooth-silhouettes.md), and the soft "
                  "shadow-map methods pcf, pcss, smoothie (docs/smoothies.md; baselines like shadowmap, their lit "
                  "mask where the light is at least 1/2), and the ray-traced peers rt, rt-robust (Embree on the CPU, "
                  "no GL; docs/ray-tracing.md; their hard errors reported, never a failure); default: all, the first six");
  add_silhouette_options(*cmd, options->silhouette);
  cmd->add_option("--stencil", options->stencil,
                  "Stencil counting of the volume methods: zfail (default; faces behind the visible point), zpass "
                  "(faces in front of it) or auto (per light, zpass where it is proven exactly for this camera, "
                  "else zfail; the reasons are printed and written to --json)")
      ->check(CLI::IsMember({"auto", "zpass", "zfail"}));
  cmd->add_flag("--zfail", options->zfail, "Alias of --stencil zfail");
  cmd->add_flag("--zpass", options->zpass, "Alias of --stencil zpass");
  cmd->add_option("--size", options->size, "Image size WxH (default: the scene camera's)");
  cmd->add_option("--out", options->out,
                  "Write into this folder: exact_mask/_counts/_ambiguous.png, METHOD_mask.png and "
                  "METHOD_overlay.png (hard errors red, ambiguous yellow; _lightK suffixes with several lights) "
                  "and summary.json");
  cmd->add_option("--json", options->json_file, "Write the summary (per method hard_errors, ambiguous, agree, "
                                                "closed, gl_ms; exact_seconds) as JSON");
  cmd->add_option("--report", options->report,
                  "Write one self-contained HTML page (images inlined) with the images side by side and the table");
  cmd->add_option("--shadowmap-size", options->shadowmap_size, "shadowmap: side of the depth map in texels")
      ->capture_default_str();
  cmd->add_option("--sign", options->sign, "cs, gs, ts, pertri: each triangle's light side as the exact sign of its float inputs (exact: a proven float filter, integer arithmetic where it cannot decide) or the float formula's sign (float: Milet 2014 refedge, wrong where the light is within rounding of a plane)")
      ->check(CLI::IsMember({"exact", "float"}))
      ->capture_default_str();
  cmd->add_option("--pcf", options->pcf, "pcf: K x K taps, K odd in [1, 15] (default 3)");
  cmd->add_option("--light-radius", options->light_radius,
                  "pcss and --soft: a point light's radius R in world units (default 1% of the scene's bounding-box "
                  "diagonal)");
  cmd->add_option("--light-angle", options->light_angle, std::string("pcss and --soft: ") + kLightAngleHelp);
  cmd->add_option("--smoothie-width", options->smoothie_width,
                  "smoothie: the width D in world units (default 2% of the scene's bounding-box diagonal)");
  cmd->add_option("--smoothie-space", options->smoothie_space, "smoothie: world or light (render --help)")
      ->check(CLI::IsMember({"world", "light"}))
      ->capture_default_str();
  cmd->add_flag("--soft", options->soft,
                "Also compute every light's exact soft reference (a disk light of --light-radius around a point "
                "light, of --light-angle about a directional one; --samples stratified samples, each light's "
                "light the mean of their exact verdicts, a pixel's 95% half-width 1.358 / sqrt(K); "
                "docs/smoothies.md) and compare every method's light image with it: mean and max error, inside "
                "the umbra, the penumbra and outside, leaks at contact, acne, and the reference's own noise "
                "(reported, never a failure)");
  cmd->add_flag("--edges", options->edges,
                "Also score every edge-map filter (diagonal, c1, sobel) against the exact edge ground truth: "
                "precision, recall and F1 per class at 1 px, 2 px and bsds, false edges on grazing surfaces "
                "(docs/edge-maps.md#scores; reported, never a failure)");
  cmd->add_option("--samples", options->samples, "--soft: sample lights on the disk, a perfect square (64 = 8 x 8)")
      ->capture_default_str();
  cmd->add_option("--device", options->device, "Use EGL device N (default: a hardware device, else llvmpipe)");
  cmd->add_option("--threads", options->threads, kThreadsHelp)->capture_default_str();
  cmd->callback([options, &exit_code] { exit_code = run_diff(*options); });
}

}  // namespace shadowcert::cli
