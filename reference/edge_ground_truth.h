#pragma once
// The exact ground truth of an edge map (docs/edge-maps.md#the-exact-ground-truth): per pixel and per class, whether a visible edge of that class passes through
// the pixel's footprint, for a soup seen by a camera.
//
// Classes (exact/view_edges.h on the canonical soup, the eye as a point light): PROFILE edges are
// silhouette or border edges, INNER edges are creases (bend above the threshold). Visibility is
// exact hidden-line removal (reference/detail/edge_visibility.h): a point X of an edge is
// visible when no triangle (every triangle of the soup, casting or not) meets the segment from
// the eye to X, but the triangles whose plane holds the whole edge (its own faces) and those
// seen edge-on, which cover no area of the image. The footprint of pixel (i, r) is its eye
// pyramid: the cone from the eye spanned by its four corner rays (core/pixel_ray.h, the rays
// of the exact image, reference/exact_image.h), which tile the view exactly.
//
//   edge      : the visible part of an edge of the class meets the open pyramid (a piece of
//               positive length passes through the pixel);
//   excluded  : not an edge pixel, but the visible part of an edge of the class meets the
//               closed pyramid: it only touches the pixel, along a face shared with a
//               neighbour (an edge exactly on the boundary between two pixels) or at a
//               corner ray. Such pixels are left out of the scores (reference/edge_scores.h),
//               like the diff's ambiguous pixels;
//   none      : otherwise.
// Every decision is an exact sign (interval filters, Mpzf), so the image does not change under
// vertex relabelling or face reversal (silhouettes and borders depend on positions only;
// creases too, the bend angle being measured across the edge), nor under an exact translation
// of soup and camera. Only the search for candidate pixels runs in double, with a margin of a
// pixel around each visible piece's projection: it proposes, never decides.
//
// The exact image's first hits come with it (reference/exact_image.h, no light): the centre
// ray's hit triangle per pixel, and whether the surface there is seen at a GRAZING angle (the
// incidence angle between the centre ray and the hit triangle's normal strictly above
// EdgeGroundTruthOptions::grazing_degrees, exact/normal_angle.h), where outline shaders are
// known to draw false edges: the scores count false edges there on their own.
#include <cstdint>
#include <span>
#include <vector>

#include "core/camera.h"
#include "core/soup.h"

namespace shadowcert {

// Per pixel and class.
enum class EdgeTruth : std::uint8_t { none = 0, edge = 1, excluded = 2 };

struct EdgeGroundTruthOptions {
  double crease_degrees = 30.0;   // a crease bends strictly more (exact/view_edges.h)
  double grazing_degrees = 80.0;  // a grazing pixel: incidence strictly above this
  // Also trace the corner rays and footprints of the exact image and count the edge pixels
  // whose footprint it proves to see one triangle only (EdgeGroundTruthStats::unseen_edge_pixels,
  // which must be 0: a visible edge in a pixel means the footprint sees two sides of it).
  // About twice the exact image's time; for tests and checks.
  bool check_footprints = false;
};

struct EdgeGroundTruthStats {
  std::uint64_t profile_edges = 0;   // silhouette or border edges of the canonical soup
  std::uint64_t inner_edges = 0;     // crease edges
  std::uint64_t visible_profile_edges = 0;  // with a visible piece
  std::uint64_t visible_inner_edges = 0;
  std::uint64_t hidden_intervals = 0;   // occluders' intervals found over all edges
  std::uint64_t pixels_tested = 0;      // exact pyramid tests
  std::uint64_t unseen_edge_pixels = 0;  // with check_footprints: must be 0
  double class_seconds = 0.0;    // canonical soup, edge table, classes
  double image_seconds = 0.0;    // the exact image's first hits (and footprints)
  double visibility_seconds = 0.0;  // hidden intervals and pyramids
  double seconds = 0.0;
};

struct EdgeGroundTruth {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  // Row-major, row 0 at the TOP (as gpu/image.h): EdgeTruth per pixel.
  std::vector<EdgeTruth> profile;
  std::vector<EdgeTruth> inner;
  // 1 where the centre ray's first hit is a triangle seen at a grazing angle (a degenerate
  // first contact, kZeroSign, never is), else 0.
  std::vector<std::uint8_t> grazing;
  std::vector<std::uint32_t> hit_triangles;  // the exact image's centre hits (kNoHit: none)
  EdgeGroundTruthStats stats;

  [[nodiscard]] std::span<const EdgeTruth> truth(bool inner_class) const { return inner_class ? inner : profile; }
};

// The ground truth of `soup` (world space, every triangle seen) for `camera`. Parallel (TBB).
// Throws std::invalid_argument("edge_ground_truth: ...") for an index out of range, a
// non-finite coordinate, a degenerate camera, or an angle outside [0, 180] degrees.
[[nodiscard]] EdgeGroundTruth edge_ground_truth(const Soup& soup, const Camera& camera,
                                                const EdgeGroundTruthOptions& options = {});

}  // namespace shadowcert
