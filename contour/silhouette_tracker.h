#pragma once
// Silhouette tracking (Chen and Tsai, §2.1; docs/smoothies.md, "Silhouette tracking"): a light
// moves frame by frame, and each frame's silhouette edges (contour/silhouette_edge_graph.h) are
// found from the previous frame's instead of by testing every edge.
//
// A frame of a tracking variant (one-way, continue, periodic:T off its full frames):
//   1. test every edge of the previous frame's list: the ones still silhouette edges survive,
//      the others are dropped;
//   2. test every edge of the concave list and of the border list (a concave silhouette can
//      appear with no neighbour on the old list, the paper's §2.1), adding the silhouette ones;
//   3. when nothing was found by 1 and 2, test edges in index order up to the first silhouette
//      edge (the paper's starting edge E0);
//   4. search from those seeds, per the variant (contour/tracking_variant.h):
//      - one-way: for each seed in turn, test its untested neighbours (the edges at its two
//        ends, in the order of SilhouetteEdgeGraph::edges_at); from each silhouette edge found
//        there, walk: stop when the current edge touches a silhouette edge already found other
//        than the one it came from (the paper: "they end check when they meet a checked
//        silhouette edge"); else test the current edge's untested neighbours, those at the end
//        it did not come in by first, up to the first silhouette edge, add it and step to it
//        (one way: the others stay untested); stop when there is none. A seed looks both
//        ways (the paper's Figure 1 repairs a gap from the survivors on both sides), so on a
//        convex mesh, whose vertices never join more than two silhouette edges, every gap
//        next to a survivor is walked to its end;
//      - continue: test every untested neighbour of every silhouette edge found, the new ones
//        included, until none is left (the connected silhouette edges around every seed).
// The first frame, every frame of `full` and every T-th frame of periodic:T test every edge.
// No edge is tested twice in a frame; each face's side is computed at most once per frame.
#include <array>
#include <cstdint>
#include <vector>

#include "contour/silhouette_edge_graph.h"
#include "contour/tracking_variant.h"
#include "core/light.h"

namespace shadowcert {

struct TrackedFrame {
  std::vector<std::uint32_t> edges;  // the silhouette edges found, in the order they were found
  std::uint64_t edges_checked = 0;   // edges tested this frame
  std::uint64_t faces_evaluated = 0;  // faces whose light side was computed this frame
  bool full_search = false;          // every edge was tested
};

class SilhouetteTracker {
 public:
  // Keeps a reference to `graph`, which must outlive the tracker. Throws
  // std::invalid_argument("SilhouetteTracker: ...") for periodic with period 0.
  SilhouetteTracker(const SilhouetteEdgeGraph& graph, TrackingVariant variant);

  // The next frame's silhouette for `light`; valid until the next call. Precondition
  // (std::invalid_argument("SilhouetteTracker::track: ...")): the light is defined (core/light.h).
  const TrackedFrame& track(const Light& light);

  // Continue as if the previous frame had found `previous` (edge indices, each < edge_count()):
  // the next track() is a tracking frame (unless the variant searches fully then). For tests and
  // for starting from a known list. Throws std::invalid_argument on an index out of range.
  void resume_from(std::vector<std::uint32_t> previous);

  [[nodiscard]] const TrackingVariant& variant() const { return variant_; }
  [[nodiscard]] std::uint64_t frames_tracked() const { return frame_; }

 private:
  // Per-frame marks: a stamp of the frame (now_) with the result in the low bits, one array
  // access per test. Stamps stay below 2^30 (they restart, every mark cleared, when they reach it).
  static constexpr std::uint32_t kStampLimit = 1u << 30;
  void begin_frame();
  void full_search(const Light& light);
  void tracking_search(const Light& light);
  bool check(std::uint32_t edge, const Light& light);  // tests the edge (once per frame)
  Sign side(std::uint32_t face, const Light& light);
  [[nodiscard]] bool tested(std::uint32_t edge) const { return (edges_[edge].mark >> 1) == now_; }
  [[nodiscard]] bool found(std::uint32_t edge) const { return edges_[edge].mark == ((now_ << 1) | 1u); }
  // Whether `edge` touches a silhouette edge found this frame other than `previous`.
  [[nodiscard]] bool touches_found(std::uint32_t edge, std::uint32_t previous) const;
  // The first untested neighbour of `edge` that tests silhouette (kBorder: none), the end away
  // from `previous` first.
  std::uint32_t next_on_walk(std::uint32_t edge, std::uint32_t previous, const Light& light);
  void walk_one_way(std::uint32_t seed, const Light& light);
  void search_continue(const Light& light);

  const SilhouetteEdgeGraph* graph_;
  TrackingVariant variant_;
  std::uint64_t frame_ = 0;  // frames tracked so far (the next one's index)
  std::uint32_t now_ = 0;    // stamp of the current frame
  // Per edge, its faces (SilhouetteEdgeGraph::edge_faces) beside its mark, (stamp << 1) |
  // silhouette: a test reads one cache line for the edge.
  struct EdgeState {
    std::array<std::uint32_t, 2> faces;
    std::uint32_t mark;
  };
  std::vector<EdgeState> edges_;
  std::vector<std::uint32_t> face_mark_;    // (stamp << 2) | (side + 1)
  std::vector<std::uint32_t> vertex_mark_;  // stamp: continue searched around the vertex
  std::vector<Sign> face_side_;             // a full search's sides
  std::vector<std::uint32_t> previous_;
  TrackedFrame current_;
};

}  // namespace shadowcert
