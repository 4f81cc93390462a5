#pragma once
// Silhouette tracking (contour/silhouette_tracker.h) held to the exact silhouette, frame by
// frame (`shadowcert track`, bench/silhouette_tracking_bench.cpp; docs/smoothies.md,
// "Silhouette tracking").
//
// The exact silhouette of a frame is the mesh's edges with exact multiplicity m != 0
// (exact/edge_multiplicity.h on the mesh's canonical soup, scene/canonical_soup.h, and its edge
// table, scene/edge_table.h), mapped to the tracker's edges by welded vertex position (both
// weld exactly, so both have the same vertices and, on a qualifying mesh, the same edges).
// Per frame and variant:
//   missed          exact silhouette edges not on the tracked list;
//   false positives edges on the list that are not exact silhouette edges (the float light
//                   side of contour/silhouette_edge_graph.h disagreeing with the exact one);
//   miss rate       missed / exact silhouette edges (0 when there are none);
//   oldest miss     how many consecutive frames, this one included, the longest-missing edge of
//                   this frame has been missing (0 when none is missed).
// A mesh that is not an oriented 2-manifold (contour/smooth_caster.h) has no face pairs to
// track: it is not tracked, its report says why, and its silhouette is found by the exact full
// search alone (ExactSearchFrame::fallback_*).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "contour/silhouette_edge_graph.h"
#include "contour/tracking_variant.h"
#include "core/light.h"
#include "core/soup.h"
#include "scene/edge_table.h"

namespace shadowcert {

// One mesh, ready for tracking and for its exact silhouette.
struct TrackingMesh {
  std::string name;
  std::size_t triangles = 0;
  Soup canonical;   // scene/canonical_soup.h of the mesh
  EdgeTable table;  // its edge table
  // Set iff the mesh qualifies (an oriented 2-manifold, borders allowed).
  std::optional<SilhouetteEdgeGraph> graph;
  std::string qualification;  // CasterQualification::summary(): "qualifies", or why not
  std::vector<std::uint32_t> graph_edge;  // per table edge: the graph's edge (graph set)

  [[nodiscard]] bool tracked() const { return graph.has_value(); }
};

// Preconditions (std::invalid_argument("tracking_mesh: ...")): indices in range, finite vertices.
[[nodiscard]] TrackingMesh tracking_mesh(std::string name, const Soup& soup);

// One frame of one variant, the tracked meshes together.
struct TrackingFrameRecord {
  std::uint64_t edges_checked = 0;
  std::uint64_t faces_evaluated = 0;
  double milliseconds = 0.0;  // the trackers' time (wall clock), not the exact comparison's
  bool full_search = false;   // every tracked mesh tested every edge
  std::size_t found = 0;      // edges on the tracked lists
  std::size_t exact = 0;      // exact silhouette edges
  std::size_t missed = 0;
  std::size_t false_positives = 0;
  std::uint32_t oldest_miss = 0;

  [[nodiscard]] double miss_rate() const { return exact == 0 ? 0.0 : static_cast<double>(missed) / static_cast<double>(exact); }
};

struct TrackingSummary {
  std::size_t frames = 0;
  double mean_miss_rate = 0.0, max_miss_rate = 0.0;
  std::size_t frames_with_misses = 0;
  std::size_t missed = 0, false_positives = 0;  // over all frames
  std::uint32_t oldest_miss = 0;                // over all frames
  double mean_edges_checked = 0.0, mean_found = 0.0, mean_exact = 0.0;
  double mean_milliseconds = 0.0;
};

struct VariantTracking {
  TrackingVariant variant;
  std::vector<TrackingFrameRecord> frames;

  [[nodiscard]] TrackingSummary summary() const;
};

// The exact full search of one frame (exact_multiplicities, the edge table built beforehand).
struct ExactSearchFrame {
  double tracked_milliseconds = 0.0, fallback_milliseconds = 0.0;  // on the tracked meshes / the others
  std::size_t tracked_edges = 0, fallback_edges = 0;               // their edges with m != 0
};

struct TrackingComparison {
  std::vector<VariantTracking> variants;  // in the order asked
  std::vector<ExactSearchFrame> exact;    // per frame
};

// Every variant tracks every tracked mesh along `lights` (frame i lit by lights[i]), each with its
// own tracker. Preconditions (std::invalid_argument("compare_tracking: ...")): every light
// defined, no periodic variant with period 0.
[[nodiscard]] TrackingComparison compare_tracking(std::span<const TrackingMesh> meshes, std::span<const Light> lights,
                                                  std::span<const TrackingVariant> variants);

}  // namespace shadowcert
