#include "pipeline/bench_suite.h"

#include <fmt/core.h>

#include <algorithm>
#include <numeric>
#include <chrono>
#include <map>
#include <set>
#include <stdexcept>
#include <utility>

#include "core/eye_frame.h"
#include "core/input_error.h"
#include "gpu/edge_style.h"
#include "gpu/offscreen_target.h"
#include "gpu/shadow_map_renderer.h"
#include "io/scene_input.h"
#include "io/soup_file.h"
#include "pipeline/analytic_comparison.h"
#include "pipeline/comparison_pictures.h"
#include "pipeline/edge_map_pictures.h"
#include "pipeline/mesh_palette.h"
#include "pipeline/method_registry.h"
#include "pipeline/ray_traced_comparison.h"
#include "pipeline/method_inputs.h"
#include "pipeline/silhouette_volumes.h"
#include "pipeline/soft_reference.h"
#include "pipeline/soft_shadow_pictures.h"
#include "scene/framed_scene.h"
#include "scene/merged_soup.h"

namespace shadowcert {
namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// The size a framed or generated scene gets without --size.
constexpr std::uint32_t kDefaultWidth = 256, kDefaultHeight = 192;

// Every light's soft errors as one: counts summed, means weighted by the pixels they are over.
SoftShadowErrors combined(const std::vector<SoftShadowErrors>& parts) {
  SoftShadowErrors out;
  const auto mean = [&](std::uint64_t SoftShadowErrors::*count, double SoftShadowErrors::*value) {
    double sum = 0.0;
    std::uint64_t n = 0;
    for (const SoftShadowErrors& p : parts) {
      sum += p.*value * static_cast<double>(p.*count);
      n += p.*count;
    }
    out.*count = n;
    out.*value = n == 0 ? 0.0 : sum / static_cast<double>(n);
  };
  mean(&SoftShadowErrors::compared, &SoftShadowErrors::mean_error);
  mean(&SoftShadowErrors::compared, &SoftShadowErrors::mean_signed_error);
  mean(&SoftShadowErrors::umbra, &SoftShadowErrors::umbra_mean_error);
  mean(&SoftShadowErrors::penumbra, &SoftShadowErrors::penumbra_mean_error);
  mean(&SoftShadowErrors::outside_penumbra, &SoftShadowErrors::outside_penumbra_mean_error);
  mean(&SoftShadowErrors::turned_away, &SoftShadowErrors::turned_away_mean_error);
  // The reference's noise is a mean over the compared pixels too; a pixel's half-width is the
  // widest light's (the one with the fewest samples).
  mean(&SoftShadowErrors::compared, &SoftShadowErrors::reference_noise);
  for (const SoftShadowErrors& p : parts) {
    out.reference_ci95 = std::max(out.reference_ci95, p.reference_ci95);
    out.reference_only += p.reference_only;
    out.method_only += p.method_only;
    out.max_error = std::max(out.max_error, p.max_error);
    out.contact += p.contact;
    out.leaks += p.leaks;
    out.lit_facing += p.lit_facing;
    out.acne += p.acne;
  }
  return out;
}

// `into` += `t`, stage by stage (medians, minima and maxima summed: every light's frames).
void add_timing(gpu::FrameTiming& into, const gpu::FrameTiming& t) {
  if (into.frames == 0) {
    into = t;
    return;
  }
  const auto add = [](gpu::TimingSummary& a, const gpu::TimingSummary& b) {
    a.median_ms += b.median_ms;
    a.min_ms += b.min_ms;
    a.max_ms += b.max_ms;
  };
  for (std::size_t s = 0; s < gpu::kRenderStageCount; ++s) {
    add(into.stage_gpu[s], t.stage_gpu[s]);
    add(into.stage_wall[s], t.stage_wall[s]);
  }
  add(into.frame_gpu, t.frame_gpu);
  add(into.frame_cpu, t.frame_cpu);
  into.mean_cpu_ms += t.mean_cpu_ms;
}

// Whether every mesh was cast by discrete or the robust chain (or not at all): the run is then
// held to the robust rule (compare_scene's rule).
bool chain_shadows_only(const SilhouetteVolumes& volumes) {
  return std::all_of(volumes.casters.begin(), volumes.casters.end(), [](const SilhouetteCaster& c) {
    return !c.cast_by || *c.cast_by == gpu::ShadowMethod::discrete;
  });
}

bool any_cast_by_method(const SilhouetteVolumes& volumes) {
  return std::any_of(volumes.casters.begin(), volumes.casters.end(),
                     [](const SilhouetteCaster& c) { return c.cast_by.has_value(); });
}

std::string relative_input(const std::filesystem::path& file, const std::filesystem::path& source_dir) {
  const std::filesystem::path rel = file.lexically_relative(source_dir);
  return !rel.empty() && *rel.begin() != ".." ? rel.generic_string() : file.generic_string();
}

std::vector<std::filesystem::path> json_files(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> out;
  if (!std::filesystem::is_directory(dir)) return out;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    if (entry.is_regular_file() && entry.path().extension() == ".json") out.push_back(entry.path());
  std::sort(out.begin(), out.end());
  return out;
}

// One edge-map run: the map drawn once and scored at the filter's default thresholds, then its
// frames (G-buffer, filter, the plain `edges` style) timed by gpu::time_edge_frames.
BenchRun edge_run(const BenchVariant& variant, const EdgeGroundTruth& truth,
                  const std::vector<gpu::ShadedSoupPart>& parts, const gpu::OffscreenTarget& target, const Scene& drawn,
                  const BenchOptions& options) {
  BenchRun b;
  b.variant = variant;
  b.run.method = gpu::ShadowMethod::shadowmap;  // no volume; the run has no light (no lit-mask comparison)
  b.run.held_robust = false;
  const gpu::EdgeFilter filter = variant.edge_filter;
  const Clock::time_point build_start = Clock::now();
  gpu::EdgeMapRenderer edges(parts);
  gpu::EdgeStyleRenderer style;
  b.build_ms = ms_since(build_start);
  gpu::EdgeMapImage map = edges.render(target, drawn.camera, filter);
  BenchEdgeScores scores;
  const EdgeChannelThresholds fixed = default_edge_channel_thresholds(filter);  // `shadowcert edges`'s
  scores.profile_threshold = fixed.profile;
  scores.inner_threshold = fixed.inner;
  const std::vector<EdgeTolerance> one_pixel{standard_edge_tolerances().front()};
  scores.profile = score_at_thresholds(truth, map, EdgeClass::profile, fixed, one_pixel).front();
  scores.inner = score_at_thresholds(truth, map, EdgeClass::inner, fixed, one_pixel).front();
  if (options.images) {
    const EdgeClassImages profile = edge_class_images(truth, map, EdgeClass::profile);
    const EdgeScoreInput input{truth.width, truth.height, profile.truth, truth.grazing, profile.intensity};
    b.overlay = edge_verdict_picture(truth, edge_verdicts(input, one_pixel.front().radius, scores.profile_threshold));
  }
  b.edges = scores;
  gpu::EdgeStyleOptions style_options;
  style_options.profile_threshold = scores.profile_threshold;
  style_options.inner_threshold = scores.inner_threshold;
  if (!drawn.lights.empty()) style_options.light = drawn.lights.front();
  b.timing = gpu::time_edge_frames(edges, style, target, drawn.camera, filter, gpu::EdgeStyle::edges, style_options,
                                   options.warm_up_frames, options.frames, options.sync);
  if (options.progress) {
    const EdgeMatchCounts c = scores.pooled();
    options.progress(fmt::format("{}: precision {:.3f}, recall {:.3f}, F1 {:.3f}, {:.2f} ms per frame", variant.id,
                                 c.precision(), c.recall(), c.f1(),
                                 options.sync == gpu::StageSync::finish ? b.timing.frame_cpu.median_ms
                                                                        : b.timing.frame_gpu.median_ms));
  }
  return b;
}

// A ray-traced run (pipeline/ray_traced_comparison.h) on the world scene, as diff runs it: its
// comparisons and soft errors from the first image, then warm_up_frames + frames images timed,
// each its BVH builds (build_ms: their median) and its rays (a frame, every light at once).
BenchRun ray_traced_run(const BenchVariant& variant, const Scene& scene, const std::string& scene_name,
                        const ExactImage& exact, std::span<const SoftReference> soft, const BenchOptions& options) {
  BenchRun b;
  b.variant = variant;
  b.run.held_robust = false;
  RayTracedRun run = compare_ray_traced(scene, variant.ray_traced, exact, soft);
  std::vector<SoftShadowErrors> soft_errors;
  for (std::size_t k = 0; k < run.lights.size(); ++k) {
    LightRun& l = run.lights[k];
    if (l.soft) soft_errors.push_back(*l.soft);
    if (options.images && k == 0) {
      b.overlay = error_overlay(l.frame.colour, l.comparison);
      if (!soft.empty()) b.soft_error = soft_error_image(soft[k].image, l.frame.first_light);
    }
    l.frame = {};
    l.comparison.verdicts = {};
    b.run.lights.push_back(std::move(l));
  }
  if (!soft_errors.empty()) b.soft = combined(soft_errors);
  std::vector<double> build_ms, trace_ms;
  for (std::size_t f = 0; f < options.warm_up_frames + options.frames; ++f) {
    const raytrace::RayTracedImage image = ray_traced_scene_image(scene, variant.ray_traced);
    if (f < options.warm_up_frames) continue;
    build_ms.push_back(1000.0 * image.stats.build_seconds);
    trace_ms.push_back(1000.0 * image.stats.trace_seconds);
  }
  if (!trace_ms.empty()) {
    b.build_ms = gpu::summarize(build_ms).median_ms;
    b.timing.frames = trace_ms.size();
    b.timing.sync = options.sync;
    b.timing.frame_cpu = gpu::summarize(trace_ms);
    b.timing.frame_gpu = b.timing.frame_cpu;  // no GPU: the same wall time under either sync
    b.timing.mean_cpu_ms = std::accumulate(trace_ms.begin(), trace_ms.end(), 0.0) / static_cast<double>(trace_ms.size());
  }
  if (options.progress)
    options.progress(fmt::format("{} {}: {} hard errors, trace {:.2f} ms, build {:.1f} ms (Embree, CPU)", scene_name,
                                 variant.id,
                                 b.run.sum(&PixelComparison::hard_errors), b.timing.frame_cpu.median_ms, b.build_ms));
  return b;
}

}  // namespace

std::string method_of(const BenchVariant& v) {
  if (v.family == BenchFamily::ray_traced) return std::string(ray_traced_method_name(v.ray_traced));
  return v.family == BenchFamily::edges ? "edges" : std::string(gpu::shadow_method_name(v.method));
}

std::string_view bench_family_name(BenchFamily family) {
  switch (family) {
    case BenchFamily::stencil: return "stencil";
    case BenchFamily::silhouette: return "silhouette";
    case BenchFamily::shadow_map: return "shadowmap";
    case BenchFamily::edges: return "edges";
    case BenchFamily::ray_traced: return "ray_traced";
  }
  return "stencil";
}

bool BenchVariant::robust() const {
  if (family == BenchFamily::edges || family == BenchFamily::ray_traced) return false;
  return shadowcert::robust(method) && !(gpu::builds_volume_on_gpu(method) && sign == gpu::SignMode::float32);
}

std::vector<BenchVariant> bench_variants() {
  // Every method of the registry (pipeline/method_registry.h) in its order, one run per value
  // of the parameter its entry sweeps ("cs/exact", "shadowmap/1024", "smooth/0.01"), or one run
  // named by the method when it sweeps none: a new method's runs come with its entry.
  std::vector<BenchVariant> out;
  for (const MethodEntry& entry : method_registry()) {
    BenchVariant base;
    base.method = entry.method;
    base.family = gpu::uses_shadow_map(entry.method)       ? BenchFamily::shadow_map
                  : gpu::is_silhouette_method(entry.method) ? BenchFamily::silhouette
                                                            : BenchFamily::stencil;
    base.id = std::string(entry.name());
    if (entry.sweep.parameter == SweptParameter::none) {
      out.push_back(base);
      continue;
    }
    for (std::size_t i = 0; i < entry.sweep.count; ++i) {
      BenchVariant v = base;
      v.id += "/" + std::string(entry.sweep.labels[i]);
      const double value = entry.sweep.values[i];
      switch (entry.sweep.parameter) {
        case SweptParameter::none: break;
        case SweptParameter::sign: v.sign = value == 0.0 ? gpu::SignMode::exact : gpu::SignMode::float32; break;
        case SweptParameter::shadow_map_size: v.shadow_map_size = static_cast<std::uint32_t>(value); break;
        case SweptParameter::pcf_kernel: v.pcf_kernel = static_cast<std::uint32_t>(value); break;
        case SweptParameter::smoothie_width_in_r: v.smoothie_width_in_r = value; break;
        case SweptParameter::epsilon: v.epsilon = value; break;
      }
      out.push_back(v);
    }
  }
  // The ray-traced methods (Embree on the CPU), after the GL ones as in the registry.
  for (const RayTracedEntry& entry : ray_traced_registry()) {
    BenchVariant v;
    v.family = BenchFamily::ray_traced;
    v.ray_traced = entry.method;
    v.id = std::string(entry.name);
    out.push_back(v);
  }
  // The edge-map filters (issue 14, gpu/edge_map.h), scored against the exact edges.
  for (gpu::EdgeFilter filter : gpu::kEdgeFilters) {
    BenchVariant v;
    v.family = BenchFamily::edges;
    v.edge_filter = filter;
    v.id = "edges/" + std::string(gpu::edge_filter_name(filter));
    out.push_back(v);
  }
  return out;
}

std::vector<BenchVariant> select_bench_variants(std::string_view list) {
  const std::vector<BenchVariant> all = bench_variants();
  if (list.empty() || list == "all") return all;
  std::set<std::string> wanted;
  std::size_t start = 0;
  while (start <= list.size()) {
    const std::size_t comma = std::min(list.find(',', start), list.size());
    const std::string entry(list.substr(start, comma - start));
    start = comma + 1;
    if (entry.empty()) continue;
    const bool known = std::any_of(all.begin(), all.end(), [&](const BenchVariant& v) { return v.id == entry || method_of(v) == entry; });
    if (!known) {
      std::string names;
      std::set<std::string> methods;
      for (const BenchVariant& v : all) methods.insert(method_of(v));
      for (const std::string& m : methods) names += (names.empty() ? "" : ", ") + m;
      throw std::invalid_argument("unknown method or run \"" + entry + "\" (methods: " + names +
                                  "; or a run id such as cs/float, shadowmap/1024, smooth/0.01; or all)");
    }
    wanted.insert(entry);
  }
  std::vector<BenchVariant> out;
  for (const BenchVariant& v : all)
    if (wanted.count(v.id) != 0 || wanted.count(method_of(v)) != 0) out.push_back(v);
  return out;
}

std::vector<std::string> real_meshes() {
  return {"closed_manifold/spot.obj",           "closed_manifold/nefertiti.obj",
          "soups/stanford-bunny.obj",           "soups/trimesh_bunny.ply",
          "closed_manifold/thingi10k_65004.stl", "edge_cases/trimesh_featuretype.STL"};
}

std::vector<BenchSceneSpec> bench_suite(std::string_view suite, const BenchPaths& paths) {
  std::vector<BenchSceneSpec> out;
  const auto scene_folder = [&](const std::string& name, const std::filesystem::path& dir) {
    for (const std::filesystem::path& file : json_files(dir)) {
      if (name == "default" && file.filename() == "sphere_grid_1m.json") continue;  // minutes of exact image
      BenchSceneSpec s;
      s.suite = name;
      s.name = file.stem().string();
      s.input = relative_input(file, paths.source_dir);
      s.file = file;
      out.push_back(std::move(s));
    }
  };
  const auto real = [&] {
    for (const std::string& mesh : real_meshes()) {
      BenchSceneSpec s;
      s.suite = "real";
      s.name = std::filesystem::path(mesh).stem().string();
      // The bundled meshes (data/meshes/, in every clone) before the developer ones.
      const std::filesystem::path bundled = paths.source_dir / "data" / "meshes" / mesh;
      const bool in_repository = std::filesystem::exists(bundled);
      s.file = in_repository ? bundled : paths.shared_data / mesh;
      s.input = (in_repository ? "data/meshes/" : "../shared/data/") + mesh;
      s.framed = true;
      if (!std::filesystem::exists(s.file)) s.missing = s.file.generic_string() + " is not here";
      out.push_back(std::move(s));
    }
  };
  const auto analytic = [&] {
    const std::vector<AnalyticShape> shapes = analytic_shapes();
    for (bool sun : {false, true})
      for (std::size_t i = 0; i < shapes.size(); ++i) {
        BenchSceneSpec s;
        s.suite = "analytic";
        s.name = shapes[i].name + (sun ? "-sun" : "-point");
        s.input = "generated: " + shapes[i].name + " over the floor y = -1.5, " +
                  (sun ? "sun towards (0.3, 1, 0.2)" : "point light at (1.2, 4, 0.8)");
        s.analytic_shape = i;
        s.sun = sun;
        s.receiver_plane = Plane{{0.0, kAnalyticFloorHeight, 0.0}, {0.0, 1.0, 0.0}};
        out.push_back(std::move(s));
      }
  };
  if (suite == "default" || suite == "all") scene_folder("default", paths.source_dir / "data/scenes");
  if (suite == "hard" || suite == "all") scene_folder("hard", paths.source_dir / "data/scenes/hard");
  if (suite == "real" || suite == "all") real();
  if (suite == "analytic" || suite == "all") analytic();
  if (suite != "default" && suite != "hard" && suite != "real" && suite != "analytic" && suite != "all")
    throw std::invalid_argument("bench_suite: unknown suite " + std::string(suite));
  return out;
}

std::vector<BenchSceneSpec> bench_scene_files(const std::vector<std::string>& paths, bool real) {
  std::vector<BenchSceneSpec> out;
  std::map<std::string, int> seen;
  for (const std::string& path : paths) {
    BenchSceneSpec s;
    s.suite = real ? "real" : "scenes";
    s.file = path;
    s.input = path;
    s.framed = s.file.extension() != ".json";
    s.name = s.file.stem().string();
    if (const int n = seen[s.name]++; n > 0) s.name += "-" + std::to_string(n + 1);
    out.push_back(std::move(s));
  }
  return out;
}

Scene load_bench_scene(const BenchSceneSpec& spec, std::uint32_t width, std::uint32_t height) {
  const bool sized = width != 0 && height != 0;
  if (spec.analytic_shape) {
    const std::vector<AnalyticShape> shapes = analytic_shapes();
    return analytic_shape_scene(shapes.at(*spec.analytic_shape), spec.sun ? kAnalyticSun : kAnalyticPointLight,
                                sized ? width : kDefaultWidth, sized ? height : kDefaultHeight);
  }
  if (!spec.missing.empty()) throw InputError(spec.file.string(), "no such file");
  if (spec.framed) {
    FramedMeshOptions options;
    options.width = sized ? width : kDefaultWidth;
    options.height = sized ? height : kDefaultHeight;
    return framed_mesh_scene(read_soup(spec.file), spec.input, options);
  }
  Scene scene = load_scene_or_mesh(spec.file);
  if (sized) {
    scene.camera.width = width;
    scene.camera.height = height;
  }
  return scene;
}

BenchSceneResult bench_scene(const Scene& scene, const BenchSceneSpec& spec, const std::vector<BenchVariant>& variants,
                             const BenchOptions& options) {
  BenchSceneResult result;
  bench_scene_into(result, scene, spec, variants, options);
  return result;
}

void bench_scene_into(BenchSceneResult& result, const Scene& scene, const BenchSceneSpec& spec,
                      const std::vector<BenchVariant>& variants, const BenchOptions& options) {
  result = BenchSceneResult{};
  const Clock::time_point scene_start = Clock::now();
  if (scene.lights.empty()) throw InputError(spec.input, "the scene has no light");
  const Soup merged = merged_soup(scene);
  if (merged.triangles.empty()) throw InputError(spec.input, "no triangle to render");
  result.triangles = merged.triangles.size();
  result.lights = scene.lights.size();
  result.width = scene.camera.width;
  result.height = scene.camera.height;

  // The references, once per scene: the exact image (every run), the soft reference (a
  // shadow-map run), the analytic image (a silhouette run on an analytic caster).
  double rounded_seconds = 0.0;
  const ExactImage exact = reference_image(scene, false, &rounded_seconds);
  result.exact_seconds = exact.stats.seconds + rounded_seconds;
  result.exact_image_seconds = exact.stats.seconds;
  const auto any_of_family = [&](BenchFamily f) {
    return std::any_of(variants.begin(), variants.end(), [&](const BenchVariant& v) { return v.family == f; });
  };
  // pcss's R, the soft reference's, the smoothies' unit.
  const double radius =
      options.light_radius > 0.0 ? options.light_radius : gpu::default_light_radius(gpu::soup_bounds(merged));
  // A directional light's angular radius, the same whatever the scene's scale.
  const double angle = options.light_angle_degrees > 0.0 ? options.light_angle_degrees : gpu::kDefaultLightAngleDegrees;
  std::vector<SoftReference> soft;
  if (any_of_family(BenchFamily::shadow_map)) {
    const Clock::time_point start = Clock::now();
    SoftReferenceOptions soft_options;
    soft_options.sampling.radius = radius;
    soft_options.sampling.angle_degrees = angle;
    soft_options.sampling.samples = options.soft_samples;
    for (std::size_t k = 0; k < scene.lights.size(); ++k) soft.push_back(soft_reference(scene, k, soft_options));
    result.soft_radius = radius;
    result.soft_angle_degrees = angle;
    result.soft_seconds = ms_since(start) / 1000.0;
  }
  std::optional<AnalyticShadowImage> analytic;
  if (any_of_family(BenchFamily::silhouette) && has_analytic_caster(scene)) {
    analytic = analytic_reference(scene, options.crease_angle_degrees);
    result.analytic_seconds = analytic->seconds;
    for (std::uint32_t m : analytic->analytic_casters) result.analytic_casters.push_back(scene.meshes[m].name);
  }
  if (options.images) {
    result.exact_mask = gpu::GrayImage(exact.width, exact.height);
    result.exact_mask.pixels = exact.lights[0].lit;
    result.count_scale = std::max<std::uint32_t>(1, max_count(exact, 0));
    result.exact_counts = count_colour_image(exact, 0, result.count_scale);
    result.exact_ambiguous = gpu::GrayImage(exact.width, exact.height);
    for (std::size_t p = 0; p < result.exact_ambiguous.pixels.size(); ++p)
      result.exact_ambiguous.pixels[p] = exact.lights[0].ambiguity[p] != 0 ? 255 : 0;
  }

  // GL draws the scene in its eye's frame (core/eye_frame.h), as compare_scene does.
  const Scene drawn = eye_relative_scene(scene);
  const Soup drawn_casters = merged_casters(drawn);
  const std::vector<gpu::ShadedSoupPart> parts = shaded_parts(drawn);
  const gpu::OffscreenTarget target(drawn.camera.width, drawn.camera.height);
  const gpu::SceneBounds drawn_bounds = gpu::soup_bounds(merged_soup(drawn));

  // The exact edges, once, when an edge-map run is asked for (the world scene's, every mesh seen).
  std::optional<EdgeGroundTruth> edge_truth;
  if (any_of_family(BenchFamily::edges)) {
    const Clock::time_point start = Clock::now();
    edge_truth = scene_edge_ground_truth(scene);
    result.edge_truth_seconds = ms_since(start) / 1000.0;
  }

  for (const BenchVariant& variant : variants) {
    result.running = variant.id;
    if (variant.family == BenchFamily::edges) {
      result.runs.push_back(edge_run(variant, *edge_truth, parts, target, drawn, options));
      continue;
    }
    if (variant.family == BenchFamily::ray_traced) {
      result.runs.push_back(ray_traced_run(variant, scene, spec.name, exact, soft, options));
      continue;
    }
    BenchRun b;
    b.variant = variant;
    const Clock::time_point build_start = Clock::now();
    const std::array methods{variant.method};
    MethodInputs inputs = prepare_method_inputs(drawn_casters, drawn.lights, methods);
    if (variant.method == gpu::ShadowMethod::smoothie) {
      SceneSmoothieOptions smoothie;
      b.smoothie_width = variant.smoothie_width_in_r * radius;
      smoothie.width = b.smoothie_width;
      smoothie.space = variant.smoothie_space;
      add_smoothies(inputs, drawn.lights, drawn_bounds, smoothie);
    }
    std::optional<SilhouetteVolumes> silhouette;
    if (variant.family == BenchFamily::silhouette) {
      SilhouetteOptions silhouette_options;
      silhouette_options.epsilon = variant.epsilon;
      silhouette_options.crease_angle_degrees = options.crease_angle_degrees;
      silhouette_options.near_plane = drawn.camera.near_plane;
      silhouette = silhouette_volumes(drawn.meshes, drawn.lights, variant.method, silhouette_options);
      if (!any_cast_by_method(*silhouette)) continue;  // every mesh falls back to the chain: the chain's runs
    }
    b.build_ms = ms_since(build_start);
    b.run.method = variant.method;
    b.run.held_robust = variant.robust() && (!silhouette || chain_shadows_only(*silhouette));
    if (variant.method == gpu::ShadowMethod::pcss) b.light_radius = radius;

    gpu::ShadowMethodOptions method_options;
    method_options.stencil = gpu::StencilMethod::zfail;
    method_options.light_stencil.assign(1, gpu::StencilMethod::zfail);
    method_options.sign = variant.sign;
    method_options.shadow_map_size = variant.shadow_map_size;
    method_options.pcf_kernel = variant.pcf_kernel;
    method_options.light_radius = radius;
    method_options.light_angle_degrees = angle;
    std::vector<SoftShadowErrors> soft_errors;
    std::optional<ContourError> contour;
    for (std::size_t k = 0; k < drawn.lights.size(); ++k) {
      const Clock::time_point light_start = Clock::now();
      gpu::ShadowMethodRenderer renderer(
          variant.method,
          light_scene(inputs, parts, drawn.lights, k, silhouette ? &silhouette->per_light[k] : nullptr,
                      silhouette ? &silhouette->gpu_casters : nullptr),
          method_options);
      b.build_ms += ms_since(light_start);  // the upload and shader compilation are not a frame's
      LightRun l = compare_light(renderer, exact, k, target, drawn.camera, 0);
      if (!soft.empty()) {
        l.soft = compare_soft_shadow(soft[k], l.frame.first_light);
        soft_errors.push_back(*l.soft);
      }
      if (silhouette && analytic) l.analytic = compare_analytic(*analytic, k, l.frame);
      add_timing(b.timing, renderer.time_frames(target, drawn.camera, options.warm_up_frames, options.frames, options.sync));
      if (options.images && k == 0) {
        b.overlay = error_overlay(l.frame.colour, l.comparison);
        if (!soft.empty()) b.soft_error = soft_error_image(soft[k].image, l.frame.first_light);
      }
      l.frame = {};  // the images are made; a frame per light and run would add up
      l.comparison.verdicts = {};
      b.run.lights.push_back(std::move(l));
      // The contour error is the world scene's (its ellipsoids are in world space); smooth-gpu's
      // is measured on the volumes its GPU build draws, read back (this context is current).
      if (silhouette && spec.receiver_plane) {
        const std::optional<ContourError> e =
            variant.method == gpu::ShadowMethod::smooth_gpu
                ? volume_contour_error(scene, k,
                                       smooth_gpu_caster_volumes(scene, k, variant.epsilon, options.crease_angle_degrees),
                                       *spec.receiver_plane)
                : contour_error(scene, k, variant.method, variant.epsilon, *spec.receiver_plane,
                                options.crease_angle_degrees);
        if (e) {
          if (!contour) {
            contour = e;
          } else {
            const double points = static_cast<double>(contour->points + e->points);
            contour->mean = points == 0 ? 0.0
                                        : (contour->mean * static_cast<double>(contour->points) +
                                           e->mean * static_cast<double>(e->points)) / points;
            contour->max = std::max(contour->max, e->max);
            contour->points += e->points;
          }
        }
      }
    }
    if (!soft_errors.empty()) b.soft = combined(soft_errors);
    b.contour = contour;
    if (options.progress)
      options.progress(fmt::format("{} {}: {} hard errors, {:.2f} ms per frame, build {:.1f} ms", spec.name, variant.id,
                                   b.run.sum(&PixelComparison::hard_errors),
                                   options.sync == gpu::StageSync::finish ? b.timing.frame_cpu.median_ms
                                                                          : b.timing.frame_gpu.median_ms,
                                   b.build_ms));
    result.runs.push_back(std::move(b));
  }
  result.running.clear();
  result.seconds = ms_since(scene_start) / 1000.0;
}

}  // namespace shadowcert
