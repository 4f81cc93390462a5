#include "pipeline/edge_map_comparison.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "core/eye_frame.h"
#include "gpu/edge_style.h"
#include "gpu/frame_timing.h"
#include "gpu/gpu_stage_timer.h"
#include "gpu/offscreen_target.h"
#include "pipeline/mesh_palette.h"
#include "scene/merged_soup.h"

namespace shadowcert {

std::string_view edge_class_name(EdgeClass c) {
  switch (c) {
    case EdgeClass::profile:
      return "profile";
    case EdgeClass::inner:
      return "inner";
    case EdgeClass::any:
      return "any";
  }
  throw std::invalid_argument("edge_class_name: unknown class");
}

EdgeGroundTruth scene_edge_ground_truth(const Scene& scene, double crease_degrees, double grazing_degrees) {
  EdgeGroundTruthOptions options;
  options.crease_degrees = crease_degrees;
  options.grazing_degrees = grazing_degrees;
  return edge_ground_truth(merged_soup(scene), scene.camera, options);
}

EdgeClassImages edge_class_images(const EdgeGroundTruth& truth, const gpu::EdgeMapImage& map, EdgeClass c) {
  const std::size_t n = std::size_t{truth.width} * truth.height;
  if (map.width != truth.width || map.height != truth.height || map.profile.size() != n || map.inner.size() != n)
    throw std::invalid_argument("edge_class_images: the edge map is " + std::to_string(map.width) + "x" +
                                std::to_string(map.height) + ", the ground truth " + std::to_string(truth.width) + "x" +
                                std::to_string(truth.height));
  EdgeClassImages out;
  switch (c) {
    case EdgeClass::profile:
      out.truth = truth.profile;
      out.intensity = map.profile;
      break;
    case EdgeClass::inner:
      out.truth = truth.inner;
      out.intensity = map.inner;
      break;
    case EdgeClass::any:
      out.truth.resize(n);
      out.intensity.resize(n);
      for (std::size_t p = 0; p < n; ++p) {
        const EdgeTruth a = truth.profile[p], b = truth.inner[p];
        out.truth[p] = a == EdgeTruth::edge || b == EdgeTruth::edge                 ? EdgeTruth::edge
                       : a == EdgeTruth::excluded || b == EdgeTruth::excluded ? EdgeTruth::excluded
                                                                              : EdgeTruth::none;
        out.intensity[p] = std::max(map.profile[p], map.inner[p]);
      }
      break;
  }
  return out;
}

EdgeFilterRun score_edge_map(const EdgeGroundTruth& truth, gpu::EdgeMapImage map, gpu::EdgeFilter filter,
                             std::span<const double> thresholds, std::span<const EdgeTolerance> tolerances) {
  if (map.width != truth.width || map.height != truth.height)
    throw std::invalid_argument("score_edge_map: the edge map is " + std::to_string(map.width) + "x" +
                                std::to_string(map.height) + ", the ground truth " + std::to_string(truth.width) + "x" +
                                std::to_string(truth.height));
  EdgeFilterRun run;
  run.filter = filter;
  run.map = std::move(map);
  for (const EdgeClass c : kEdgeClasses) {
    const EdgeClassImages images = edge_class_images(truth, run.map, c);
    const EdgeScoreInput input{truth.width, truth.height, images.truth, truth.grazing, images.intensity};
    auto& curves = run.curves[static_cast<std::size_t>(c)];
    for (const EdgeTolerance& tolerance : tolerances) curves.push_back(score_edges(input, tolerance, thresholds));
  }
  return run;
}

namespace {

// The medians of gpu/edge_style.h's time_edge_frames.
EdgePassTimes pass_times(const gpu::FrameTiming& t) {
  EdgePassTimes p;
  p.frames = t.frames;
  p.g_buffer_gpu = t.gpu(gpu::RenderStage::g_buffer).median_ms;
  p.filter_gpu = t.gpu(gpu::RenderStage::edge_filter).median_ms;
  p.composite_gpu = t.gpu(gpu::RenderStage::composite).median_ms;
  p.g_buffer_wall = t.wall(gpu::RenderStage::g_buffer).median_ms;
  p.filter_wall = t.wall(gpu::RenderStage::edge_filter).median_ms;
  p.composite_wall = t.wall(gpu::RenderStage::composite).median_ms;
  return p;
}

}  // namespace

EdgeMapComparison compare_edge_maps(const Scene& scene, const EdgeMapComparisonOptions& options) {
  if (options.filters.empty() || options.thresholds.empty() || options.tolerances.empty())
    throw std::invalid_argument("compare_edge_maps: filters, thresholds and tolerances must not be empty");
  EdgeMapComparison result;
  result.thresholds = options.thresholds;
  result.tolerances = options.tolerances;
  result.truth = scene_edge_ground_truth(scene, options.crease_degrees, options.grazing_degrees);
  // GL draws the scene in the eye's frame (core/eye_frame.h), as render and diff do.
  const Scene drawn = eye_relative_scene(scene);
  const std::vector<gpu::ShadedSoupPart> parts = shaded_parts(drawn);
  gpu::EdgeMapRenderer edges(parts);
  const gpu::OffscreenTarget target(drawn.camera.width, drawn.camera.height);
  std::optional<gpu::EdgeStyleRenderer> style;
  for (const gpu::EdgeFilter filter : options.filters) {
    gpu::EdgeMapImage map = edges.render(target, drawn.camera, filter);
    EdgeFilterRun run = score_edge_map(result.truth, std::move(map), filter, options.thresholds, options.tolerances);
    if (options.timed_frames > 0) {
      if (!style) style.emplace();
      gpu::EdgeStyleOptions style_options;
      if (!drawn.lights.empty()) style_options.light = drawn.lights.front();
      run.times = pass_times(gpu::time_edge_frames(edges, *style, target, drawn.camera, filter, gpu::EdgeStyle::edges,
                                                   style_options, 1, options.timed_frames, gpu::StageSync::finish));
    }
    result.runs.push_back(std::move(run));
  }
  return result;
}

double measured_edge_threshold(gpu::EdgeFilter filter, EdgeClass c) {
  // [filter][class]: bench/edge_score_bench --resolution=1024x768, "threshold (all scenes)" at 1 px.
  constexpr std::array<std::array<double, 3>, 3> kMeasured{{{0.04, 0.05, 0.1}, {0.005, 0.03, 0.03}, {0.01, 0.25, 0.25}}};
  std::size_t f = 0;
  switch (filter) {
    case gpu::EdgeFilter::diagonal:
      f = 0;
      break;
    case gpu::EdgeFilter::c1:
      f = 1;
      break;
    case gpu::EdgeFilter::sobel:
      f = 2;
      break;
  }
  return kMeasured[f][static_cast<std::size_t>(c)];
}

std::vector<EdgeScoreRow> edge_score_rows(const EdgeMapComparison& comparison) {
  std::vector<EdgeScoreRow> rows;
  if (comparison.thresholds.empty()) return rows;
  for (const EdgeFilterRun& run : comparison.runs)
    for (const EdgeClass c : kEdgeClasses) {
      const double wanted = measured_edge_threshold(run.filter, c);
      std::size_t nearest = 0;
      for (std::size_t k = 1; k < comparison.thresholds.size(); ++k)
        if (std::abs(comparison.thresholds[k] - wanted) < std::abs(comparison.thresholds[nearest] - wanted)) nearest = k;
      EdgeScoreRow row{run.filter, c, comparison.thresholds[nearest], {}};
      for (std::size_t k = 0; k < comparison.tolerances.size(); ++k) row.counts.push_back(run.curve(c, k)[nearest]);
      rows.push_back(std::move(row));
    }
  return rows;
}

EdgeChannelThresholds default_edge_channel_thresholds(gpu::EdgeFilter filter, double crease_degrees) {
  return {gpu::profile_threshold(filter, gpu::kDefaultEdgeDepthStep), gpu::inner_threshold(filter, crease_degrees)};
}

std::vector<EdgeMatchCounts> score_at_thresholds(const EdgeGroundTruth& truth, const gpu::EdgeMapImage& map,
                                                 EdgeClass c, const EdgeChannelThresholds& thresholds,
                                                 std::span<const EdgeTolerance> tolerances) {
  if (map.width != truth.width || map.height != truth.height)
    throw std::invalid_argument("score_at_thresholds: the edge map is " + std::to_string(map.width) + "x" +
                                std::to_string(map.height) + ", the ground truth " + std::to_string(truth.width) + "x" +
                                std::to_string(truth.height));
  EdgeClassImages images = edge_class_images(truth, map, c);
  double threshold = c == EdgeClass::inner ? thresholds.inner : thresholds.profile;
  if (c == EdgeClass::any) {
    // Two thresholds: the detections themselves, 1 or 0, scored at 1/2.
    for (std::size_t p = 0; p < images.intensity.size(); ++p)
      images.intensity[p] = map.profile[p] > thresholds.profile || map.inner[p] > thresholds.inner ? 1.0f : 0.0f;
    threshold = 0.5;
  }
  const EdgeScoreInput input{truth.width, truth.height, images.truth, truth.grazing, images.intensity};
  const std::array<double, 1> at{threshold};
  std::vector<EdgeMatchCounts> out;
  for (const EdgeTolerance& tolerance : tolerances) out.push_back(score_edges(input, tolerance, at).front());
  return out;
}

}  // namespace shadowcert
