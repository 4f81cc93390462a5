#pragma once
// Scores of an edge map against the exact ground truth (docs/edge-maps.md#scores): precision, recall and F1 of the thresholded intensities of one class (profile or inner)
// against that class of reference/edge_ground_truth.h, over plain row-major arrays (row 0 at
// the top), so that any detector can be scored: the GL edge maps (gpu/edge_map.h), the ground
// truth itself, a test's hand-made image.
//
// A pixel is DETECTED at threshold T when its intensity is strictly above T (gpu/edge_map.h's
// convention: a threshold of 1 detects nothing). Two ways to match detections with the truth:
//
//   window (docs/edge-maps.md#definitions): a detection is TRUE when a truth edge pixel of its class lies
//     within its (2 radius + 1)^2 window (Chebyshev distance <= radius: 3 x 3 for radius 1,
//     5 x 5 for 2, the pixel itself for 0); a truth pixel is FOUND when a detection lies in its
//     window. Many detections may match one truth pixel (a two-pixel-wide line of detections
//     along a one-pixel line of truth is all true).
//   bsds (the Berkeley segmentation benchmark, Martin et al. 2004, so that figures compare with
//     the edge-detection literature): the detections are first thinned to one-pixel lines
//     (thin_edges: morphological thinning as MATLAB's bwmorph 'thin'), the truth's edge pixels too; then
//     detections and truth pixels are matched ONE TO ONE within a Euclidean distance of
//     bsds_fraction (0.0075) of the image diagonal, as many pairs as possible (a maximum
//     bipartite matching, Hopcroft and Karp). The benchmark computes a minimum-cost assignment
//     whose count of matched pairs is that maximum; its costs only choose among them.
//
// Excluded pixels (EdgeTruth::excluded: an edge only touches the pixel) count nowhere: a
// detection on one is neither true nor false, and they are no truth to find. Precision =
// true detections / detections (1 when nothing is detected), recall = found / truth pixels
// (1 when the class has none in the image), F1 their harmonic mean (0 when both are 0).
//
// False edges on GRAZING planes (the commonest complaint against outline shaders): false
// detections on pixels the ground truth marks grazing (the centre ray meets the surface at an
// incidence above 80 degrees), counted on their own, with the number of grazing pixels off the
// truth (neither a truth edge pixel of the class nor excluded).
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "reference/edge_ground_truth.h"

namespace shadowcert {

struct EdgeMatchCounts {
  std::uint64_t detections = 0;          // detected pixels, excluded ones left out
  std::uint64_t true_detections = 0;     // of those, matched with the truth
  std::uint64_t truth = 0;               // truth edge pixels
  std::uint64_t found = 0;               // of those, matched with a detection
  std::uint64_t grazing_false = 0;       // false detections on grazing pixels
  std::uint64_t grazing_pixels = 0;      // grazing pixels off the truth (no truth edge, not excluded)

  [[nodiscard]] double precision() const;
  [[nodiscard]] double recall() const;
  [[nodiscard]] double f1() const;
  // grazing_false / grazing_pixels (0 when there is none).
  [[nodiscard]] double grazing_false_rate() const;
  EdgeMatchCounts& operator+=(const EdgeMatchCounts& other);
  friend bool operator==(const EdgeMatchCounts&, const EdgeMatchCounts&) = default;
};

enum class EdgeMatching : std::uint8_t { window, bsds };

// How detections and truth are matched: a window of Chebyshev radius `radius`, or bsds with
// the maximum distance `bsds_fraction` of the image diagonal.
struct EdgeTolerance {
  EdgeMatching matching = EdgeMatching::window;
  std::uint32_t radius = 1;
  double bsds_fraction = 0.0075;

  // "1px", "2px", "0px", "bsds".
  [[nodiscard]] std::string name() const;
};

// The tolerances every table reports: one pixel (the reference tolerance, docs/edge-maps.md#definitions), two pixels, and bsds.
[[nodiscard]] std::vector<EdgeTolerance> standard_edge_tolerances();

// The thresholds of the curve: fine where the GL filters' intensities live (an edge map's
// intensities next to a small depth step are a few hundredths), then 0.05 steps to 0.95.
[[nodiscard]] std::vector<double> default_edge_thresholds();

// One class's inputs, all width * height long, row-major, row 0 at the top.
struct EdgeScoreInput {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::span<const EdgeTruth> truth;
  std::span<const std::uint8_t> grazing;  // may be empty: no grazing pixel
  std::span<const float> intensity;       // the detector's, in [0, 1] (NaN detects nothing)
};

// The counts at each of `thresholds` (in their order). Throws std::invalid_argument
// ("score_edges: ...") when a span's size is not width * height (grazing: or empty), or for a
// bsds fraction not in (0, 1).
[[nodiscard]] std::vector<EdgeMatchCounts> score_edges(const EdgeScoreInput& input, const EdgeTolerance& tolerance,
                                                       std::span<const double> thresholds);

// What one pixel is at one threshold under window matching of Chebyshev radius `radius`, for
// pictures (pipeline/edge_map_pictures.h): the first that applies of
//   excluded         the truth excludes it (a detection there counts nowhere);
//   true_detection   detected, a truth pixel within reach;
//   false_detection  detected, no truth pixel within reach;
//   missed           a truth pixel without a detection within reach;
//   found            a truth pixel, not itself detected, with a detection within reach;
//   none.
// Their counts agree with score_edges: detections = true + false, found = truth - missed
// (a detected truth pixel is a true detection and found). Throws as score_edges.
enum class EdgeVerdict : std::uint8_t { none, excluded, true_detection, false_detection, missed, found };
[[nodiscard]] std::vector<EdgeVerdict> edge_verdicts(const EdgeScoreInput& input, std::uint32_t radius,
                                                     double threshold);

// Morphological thinning of a binary image (nonzero = set) to 8-connected lines one pixel
// wide: the two-sub-iteration algorithm of Lam, Lee and Suen (1992, p. 879; Guo and Hall's
// conditions G1-G3), which MATLAB's bwmorph(..., 'thin', Inf) implements and the benchmark
// applies to its detections. It removes, until nothing changes, the boundary pixels whose
// removal keeps the connectivity, keeping end points. Returns 1 for kept pixels, 0 elsewhere.
[[nodiscard]] std::vector<std::uint8_t> thin_edges(std::span<const std::uint8_t> mask, std::uint32_t width,
                                                   std::uint32_t height);

// The index of the threshold whose summed counts give the highest F1 (the first on a tie):
// the "optimal dataset scale" of the benchmark, over the curves of several images at the same
// thresholds. Throws std::invalid_argument when the curves are empty or differ in length.
[[nodiscard]] std::size_t best_threshold(std::span<const std::vector<EdgeMatchCounts>> curves);

}  // namespace shadowcert
