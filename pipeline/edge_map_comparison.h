#pragma once
// The GL edge maps of one scene against its exact ground truth (docs/edge-maps.md#scores): the
// part `shadowcert diff` (the edge maps in its report), bench/edge_score_bench and the tests
// share.
//
//   gpu::EglContext context = gpu::open_gl_context("diff", device);   // current on this thread
//   EdgeMapComparison c = compare_edge_maps(scene, {});               // truth, then each filter
//   c.runs[k].curves[class][tolerance][threshold]                      // EdgeMatchCounts
//   edge_score_rows(c)                 // each filter and class at the default thresholds
//
// The ground truth (reference/edge_ground_truth.h) is the world scene's, every mesh seen; GL
// draws the scene in its eye's frame (core/eye_frame.h), as every GL path does, through
// gpu/edge_map.h's EdgeMapRenderer (G-buffer and filter), once per filter. Each filter's profile
// intensities are scored against the profile truth and its inner intensities against the inner
// truth (reference/edge_scores.h), at every threshold and tolerance of the options.
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/scene.h"
#include "gpu/edge_map.h"
#include "reference/edge_ground_truth.h"
#include "reference/edge_scores.h"

namespace shadowcert {

// The classes the scores keep apart, in this order: profile (silhouette and border edges, the
// edge map's profile intensities), inner (creases, its inner intensities), and any (either
// class's truth, against the larger of the two intensities: what an outline drawn from both
// channels shows; normals also step at most profile edges, the paper's section 3, which the
// inner class counts as false edges and this one does not).
enum class EdgeClass : std::uint8_t { profile = 0, inner = 1, any = 2 };
inline constexpr std::array<EdgeClass, 3> kEdgeClasses{EdgeClass::profile, EdgeClass::inner, EdgeClass::any};
[[nodiscard]] std::string_view edge_class_name(EdgeClass c);  // "profile", "inner", "any"

// One class's truth and intensities, per pixel: for any, truth edge where either class's is,
// excluded where neither is an edge but one is excluded, and the larger intensity. Throws
// std::invalid_argument("edge_class_images: ...") when the sizes differ.
struct EdgeClassImages {
  std::vector<EdgeTruth> truth;
  std::vector<float> intensity;
};
[[nodiscard]] EdgeClassImages edge_class_images(const EdgeGroundTruth& truth, const gpu::EdgeMapImage& map, EdgeClass c);

struct EdgeMapComparisonOptions {
  std::vector<gpu::EdgeFilter> filters{gpu::kEdgeFilters.begin(), gpu::kEdgeFilters.end()};
  std::vector<double> thresholds = default_edge_thresholds();
  std::vector<EdgeTolerance> tolerances = standard_edge_tolerances();
  // The ground truth's crease threshold: gpu/edge_map.h's default, which the filters' inner
  // thresholds name too (inner_threshold), so that truth and detector mean the same crease.
  double crease_degrees = gpu::kDefaultEdgeCreaseAngleDegrees;
  double grazing_degrees = 80.0;
  // Frames drawn and timed per filter after the scored one and a warm-up frame: G-buffer,
  // filter and composite (the plain `edges` style) each timed apart (gpu/edge_style.h's
  // time_edge_frames, bounded by glFinish, so that llvmpipe's wall time is the pass's cost);
  // 0: none.
  std::size_t timed_frames = 0;
};

// Milliseconds per pass, the median over the timed frames: GPU time from timer queries and
// CPU wall time around each pass (bounded by glFinish).
struct EdgePassTimes {
  double g_buffer_gpu = 0.0, filter_gpu = 0.0, composite_gpu = 0.0;
  double g_buffer_wall = 0.0, filter_wall = 0.0, composite_wall = 0.0;
  std::size_t frames = 0;
};

struct EdgeFilterRun {
  gpu::EdgeFilter filter = gpu::EdgeFilter::diagonal;
  gpu::EdgeMapImage map;
  // curves[class][tolerance][threshold], in the order of kEdgeClasses and of the options'
  // tolerances and thresholds.
  std::array<std::vector<std::vector<EdgeMatchCounts>>, kEdgeClasses.size()> curves;
  EdgePassTimes times;

  [[nodiscard]] const std::vector<EdgeMatchCounts>& curve(EdgeClass c, std::size_t tolerance) const {
    return curves[static_cast<std::size_t>(c)][tolerance];
  }
};

struct EdgeMapComparison {
  EdgeGroundTruth truth;
  std::vector<double> thresholds;
  std::vector<EdgeTolerance> tolerances;
  std::vector<EdgeFilterRun> runs;  // one per filter, in the options' order
  // The ground truth's crease angle (the options'): the crease the default inner thresholds
  // answer (default_edge_channel_thresholds).
  double crease_degrees = gpu::kDefaultEdgeCreaseAngleDegrees;
};

// The ground truth of `scene` (merged_soup: every mesh seen) at its camera.
[[nodiscard]] EdgeGroundTruth scene_edge_ground_truth(const Scene& scene, double crease_degrees = gpu::kDefaultEdgeCreaseAngleDegrees,
                                                      double grazing_degrees = 80.0);

// `map` scored against `truth` (same size, else std::invalid_argument("score_edge_map: ...")):
// no GL, for maps rendered elsewhere and for tests.
[[nodiscard]] EdgeFilterRun score_edge_map(const EdgeGroundTruth& truth, gpu::EdgeMapImage map, gpu::EdgeFilter filter,
                                           std::span<const double> thresholds,
                                           std::span<const EdgeTolerance> tolerances);

// The ground truth and every filter on `scene`. Preconditions: a GL context is current on this
// thread; the scene has a triangle; filters, thresholds and tolerances are not empty
// (std::invalid_argument("compare_edge_maps: ...") otherwise). Throws what the renderer and the
// ground truth throw.
[[nodiscard]] EdgeMapComparison compare_edge_maps(const Scene& scene, const EdgeMapComparisonOptions& options = {});

// The thresholds `shadowcert edges` draws with by default, fixed in advance (gpu/edge_map.h):
// profile, the filter's answer to a depth step of gpu::kDefaultEdgeDepthStep; inner, its answer
// to a crease of `crease_degrees` (the ground truth's crease angle, so that both mean the same
// crease). Nothing is fitted to any image.
struct EdgeChannelThresholds {
  double profile = 0.0;
  double inner = 0.0;
};
[[nodiscard]] EdgeChannelThresholds default_edge_channel_thresholds(
    gpu::EdgeFilter filter, double crease_degrees = gpu::kDefaultEdgeCreaseAngleDegrees);

// One class's truth and what it is compared with at fixed thresholds per channel: profile and
// inner, the channel's intensities against its own threshold; any, the detections themselves (1
// where either channel is strictly above its own threshold, else 0: the outline `shadowcert
// edges` draws from both) against 1/2. Throws std::invalid_argument("edge_class_images: ...")
// when the sizes differ.
struct EdgeClassAtThresholds {
  EdgeClassImages images;
  double threshold = 0.0;  // what images.intensity is held to
};
[[nodiscard]] EdgeClassAtThresholds edge_class_at_thresholds(const EdgeGroundTruth& truth, const gpu::EdgeMapImage& map,
                                                             EdgeClass c, const EdgeChannelThresholds& thresholds);

// One class of `map` against `truth` (same size, else std::invalid_argument
// ("score_at_thresholds: ...")) at fixed thresholds per channel (edge_class_at_thresholds):
// profile intensities above `thresholds.profile`, inner above `thresholds.inner`, and for any a
// pixel where either channel is above its own. The counts at each of `tolerances`, in their
// order.
[[nodiscard]] std::vector<EdgeMatchCounts> score_at_thresholds(const EdgeGroundTruth& truth, const gpu::EdgeMapImage& map,
                                                               EdgeClass c, const EdgeChannelThresholds& thresholds,
                                                               std::span<const EdgeTolerance> tolerances);

// The thresholds a class reads, as text: profile's ("0.0394"), inner's ("0.06699"), or both for
// any ("0.0394, 0.06699"), 4 significant digits.
[[nodiscard]] std::string edge_class_thresholds_text(EdgeClass c, const EdgeChannelThresholds& thresholds);

// One filter and class of a comparison at the filter's default thresholds
// (default_edge_channel_thresholds at the comparison's crease angle: what `shadowcert edges`
// draws with, fixed before any image is seen, so that no score is taken at a threshold fitted
// on the image it scores): the counts at every tolerance, in the comparison's order. What
// `diff --edges` prints, writes to its JSON and shows in its report.
struct EdgeScoreRow {
  gpu::EdgeFilter filter = gpu::EdgeFilter::diagonal;
  EdgeClass edge_class = EdgeClass::profile;
  EdgeChannelThresholds thresholds;  // the filter's; the class reads profile's, inner's or both (any)
  std::vector<EdgeMatchCounts> counts;
};
// Per run, the classes in kEdgeClasses order.
[[nodiscard]] std::vector<EdgeScoreRow> edge_score_rows(const EdgeMapComparison& comparison);

}  // namespace shadowcert
