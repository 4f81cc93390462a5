#include "contour/silhouette_tracker.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace shadowcert {

SilhouetteTracker::SilhouetteTracker(const SilhouetteEdgeGraph& graph, TrackingVariant variant)
    : graph_(&graph),
      variant_(variant),
      face_mark_(graph.face_count(), 0),
      vertex_mark_(graph.vertices.size(), 0),
      face_side_(graph.face_count(), Sign::zero) {
  if (variant.search == TrackingSearch::periodic && variant.period == 0)
    throw std::invalid_argument("SilhouetteTracker: periodic tracking needs a period of at least 1");
  edges_.reserve(graph.edge_count());
  for (const auto& faces : graph.edge_faces) edges_.push_back({faces, 0});
}

void SilhouetteTracker::resume_from(std::vector<std::uint32_t> previous) {
  for (const std::uint32_t e : previous)
    if (e >= graph_->edge_count())
      throw std::invalid_argument("SilhouetteTracker::resume_from: edge " + std::to_string(e) + " out of range");
  previous_ = std::move(previous);
  frame_ = std::max<std::uint64_t>(frame_, 1);
}

void SilhouetteTracker::begin_frame() {
  if (++now_ == kStampLimit) {  // forget every old mark
    for (EdgeState& e : edges_) e.mark = 0;
    std::fill(face_mark_.begin(), face_mark_.end(), 0u);
    std::fill(vertex_mark_.begin(), vertex_mark_.end(), 0u);
    now_ = 1;
  }
  current_.edges.clear();
  current_.edges_checked = 0;
  current_.faces_evaluated = 0;
  current_.full_search = false;
}

Sign SilhouetteTracker::side(std::uint32_t face, const Light& light) {
  const std::uint32_t mark = face_mark_[face];
  if ((mark >> 2) == now_) return static_cast<Sign>(static_cast<int>(mark & 3u) - 1);
  const Sign s = face_light_side(*graph_, face, light);
  face_mark_[face] = (now_ << 2) | static_cast<std::uint32_t>(to_int(s) + 1);
  ++current_.faces_evaluated;
  return s;
}

bool SilhouetteTracker::check(std::uint32_t edge, const Light& light) {
  ++current_.edges_checked;
  EdgeState& state = edges_[edge];
  const bool border = state.faces[1] == kBorder;
  const bool silhouette =
      silhouette_sides(side(state.faces[0], light), border ? Sign::zero : side(state.faces[1], light), border);
  state.mark = (now_ << 1) | (silhouette ? 1u : 0u);
  if (silhouette) current_.edges.push_back(edge);
  return silhouette;
}

// No marks: nothing else is tested in a full frame, and the next frame has another stamp.
void SilhouetteTracker::full_search(const Light& light) {
  const SilhouetteEdgeGraph& g = *graph_;
  for (std::uint32_t t = 0; t < g.face_count(); ++t) face_side_[t] = face_light_side(g, t, light);
  for (std::uint32_t e = 0; e < g.edge_count(); ++e) {
    const auto& faces = g.edge_faces[e];
    const bool border = faces[1] == kBorder;
    if (silhouette_sides(face_side_[faces[0]], border ? Sign::zero : face_side_[faces[1]], border))
      current_.edges.push_back(e);
  }
  current_.edges_checked = g.edge_count();
  current_.faces_evaluated = g.face_count();
  current_.full_search = true;
}

bool SilhouetteTracker::touches_found(std::uint32_t edge, std::uint32_t previous) const {
  const SilhouetteEdgeGraph& g = *graph_;
  for (const std::uint32_t v : g.edge_vertices[edge])
    for (const std::uint32_t n : g.edges_at(v))
      if (n != edge && n != previous && found(n)) return true;
  return false;
}

std::uint32_t SilhouetteTracker::next_on_walk(std::uint32_t edge, std::uint32_t previous, const Light& light) {
  const SilhouetteEdgeGraph& g = *graph_;
  // The end the walk did not come in by first: the chain goes on there unless it forks.
  const auto& ends = g.edge_vertices[edge];
  const auto& behind = g.edge_vertices[previous];
  const bool back_first = ends[0] == behind[0] || ends[0] == behind[1];
  for (const std::uint32_t v : {back_first ? ends[1] : ends[0], back_first ? ends[0] : ends[1]})
    for (const std::uint32_t n : g.edges_at(v))
      if (n != edge && !tested(n) && check(n, light)) return n;
  return kBorder;
}

void SilhouetteTracker::walk_one_way(std::uint32_t seed, const Light& light) {
  const SilhouetteEdgeGraph& g = *graph_;
  for (const std::uint32_t end : g.edge_vertices[seed])
    for (const std::uint32_t first : g.edges_at(end)) {
      if (first == seed || tested(first) || !check(first, light)) continue;
      // A walk from each new silhouette edge next to the seed, one edge at a time.
      std::uint32_t previous = seed;
      for (std::uint32_t current = first; current != kBorder && !touches_found(current, previous);) {
        const std::uint32_t next = next_on_walk(current, previous, light);
        previous = current;
        current = next;
      }
    }
}

void SilhouetteTracker::search_continue(const Light& light) {
  const SilhouetteEdgeGraph& g = *graph_;
  // current_.edges grows while it is walked: every edge found gets its neighbours tested.
  for (std::size_t i = 0; i < current_.edges.size(); ++i) {
    for (const std::uint32_t v : g.edge_vertices[current_.edges[i]]) {
      if (vertex_mark_[v] == now_) continue;  // its edges are tested already
      vertex_mark_[v] = now_;
      for (const std::uint32_t n : g.edges_at(v))
        if (!tested(n)) check(n, light);
    }
  }
}

void SilhouetteTracker::tracking_search(const Light& light) {
  const SilhouetteEdgeGraph& g = *graph_;
  for (const std::uint32_t e : previous_)
    if (!tested(e)) check(e, light);
  for (const auto* list : {&g.concave_edges, &g.border_edges})
    for (const std::uint32_t e : *list)
      if (!tested(e)) check(e, light);
  if (current_.edges.empty())  // the paper's starting edge E0
    for (std::uint32_t e = 0; e < g.edge_count(); ++e)
      if (!tested(e) && check(e, light)) break;
  if (variant_.search == TrackingSearch::continue_search) {
    search_continue(light);
    return;
  }
  const std::size_t seeds = current_.edges.size();
  for (std::size_t i = 0; i < seeds; ++i) walk_one_way(current_.edges[i], light);
}

const TrackedFrame& SilhouetteTracker::track(const Light& light) {
  require_defined(light, "SilhouetteTracker::track");
  begin_frame();
  const bool full = frame_ == 0 || variant_.search == TrackingSearch::full ||
                    (variant_.search == TrackingSearch::periodic && frame_ % variant_.period == 0);
  if (full) full_search(light);
  else tracking_search(light);
  previous_ = current_.edges;
  ++frame_;
  return current_;
}

}  // namespace shadowcert
