#include "pipeline/edge_map_comparison.h"

#include <fmt/core.h>

#include <algorithm>
#include <array>
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
  result.crease_degrees = options.crease_degrees;
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

EdgeChannelThresholds default_edge_channel_thresholds(gpu::EdgeFilter filter, double crease_degrees) {
  return {gpu::profile_threshold(filter, gpu::kDefaultEdgeDepthStep), gpu::inner_threshold(filter, crease_degrees)};
}

EdgeClassAtThresholds edge_class_at_thresholds(const EdgeGroundTruth& truth, const gpu::EdgeMapImage& map,
                                               EdgeClass c, const EdgeChannelThresholds& thresholds) {
  EdgeClassAtThresholds out{edge_class_images(truth, map, c), c == EdgeClass::inner ? thresholds.inner : thresholds.profile};
  if (c == EdgeClass::any) {
    // Two thresholds: the detections themselves, 1 or 0, held to 1/2.
    for (std::size_t p = 0; p < out.images.intensity.size(); ++p)
      out.images.intensity[p] = map.profile[p] > thresholds.profile || map.inner[p] > thresholds.inner ? 1.0f : 0.0f;
    out.threshold = 0.5;
  }
  return out;
}

std::vector<EdgeMatchCounts> score_at_thresholds(const EdgeGroundTruth& truth, const gpu::EdgeMapImage& map,
                                                 EdgeClass c, const EdgeChannelThresholds& thresholds,
                                                 std::span<const EdgeTolerance> tolerances) {
  if (map.width != truth.width || map.height != truth.height)
    throw std::invalid_argument("score_at_thresholds: the edge map is " + std::to_string(map.width) + "x" +
                                std::to_string(map.height) + ", the ground truth " + std::to_string(truth.width) + "x" +
                                std::to_string(truth.height));
  const EdgeClassAtThresholds at = edge_class_at_thresholds(truth, map, c, thresholds);
  const EdgeScoreInput input{truth.width, truth.height, at.images.truth, truth.grazing, at.images.intensity};
  const std::array<double, 1> threshold{at.threshold};
  std::vector<EdgeMatchCounts> out;
  for (const EdgeTolerance& tolerance : tolerances) out.push_back(score_edges(input, tolerance, threshold).front());
  return out;
}

std::string edge_class_thresholds_text(EdgeClass c, const EdgeChannelThresholds& thresholds) {
  switch (c) {
    case EdgeClass::profile:
      return fmt::format("{:.4g}", thresholds.profile);
    case EdgeClass::inner:
      return fmt::format("{:.4g}", thresholds.inner);
    case EdgeClass::any:
      return fmt::format("{:.4g}, {:.4g}", thresholds.profile, thresholds.inner);
  }
  throw std::invalid_argument("edge_class_thresholds_text: unknown class");
}

std::vector<EdgeScoreRow> edge_score_rows(const EdgeMapComparison& comparison) {
  std::vector<EdgeScoreRow> rows;
  for (const EdgeFilterRun& run : comparison.runs) {
    const EdgeChannelThresholds fixed = default_edge_channel_thresholds(run.filter, comparison.crease_degrees);
    for (const EdgeClass c : kEdgeClasses)
      rows.push_back({run.filter, c, fixed, score_at_thresholds(comparison.truth, run.map, c, fixed, comparison.tolerances)});
  }
  return rows;
}

}  // namespace shadowcert
