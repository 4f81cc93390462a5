#include "pipeline/silhouette_tracking.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <utility>

#include "contour/silhouette_tracker.h"
#include "contour/smooth_caster.h"
#include "exact/edge_multiplicity.h"
#include "scene/canonical_soup.h"

namespace shadowcert {
namespace {

using Clock = std::chrono::steady_clock;

double milliseconds_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// Per table edge, the graph's edge with the same two welded positions.
std::vector<std::uint32_t> graph_edges_of_table(const Soup& canonical, const EdgeTable& table,
                                                const SilhouetteEdgeGraph& graph) {
  if (table.size() != graph.edge_count())
    throw std::logic_error("tracking_mesh: the edge table and the edge graph of a qualifying mesh differ in size");
  // Canonical vertices are the welded positions in lexicographic order: find each graph vertex there.
  std::vector<std::uint32_t> graph_vertex(canonical.vertices.size(), kBorder);
  for (std::uint32_t v = 0; v < graph.vertices.size(); ++v) {
    const auto it = std::lower_bound(canonical.vertices.begin(), canonical.vertices.end(), graph.vertices[v]);
    if (it == canonical.vertices.end() || *it != graph.vertices[v])
      throw std::logic_error("tracking_mesh: a welded vertex is missing from the canonical soup");
    graph_vertex[static_cast<std::size_t>(it - canonical.vertices.begin())] = v;
  }
  std::vector<std::uint32_t> out(table.size());
  for (std::size_t e = 0; e < table.size(); ++e) {
    const std::uint32_t a = graph_vertex[table.edges[e][0]], b = graph_vertex[table.edges[e][1]];
    const std::array<std::uint32_t, 2> ends{std::min(a, b), std::max(a, b)};
    const auto around = graph.edges_at(ends[0]);
    const auto it = std::find_if(around.begin(), around.end(), [&](std::uint32_t g) { return graph.edge_vertices[g] == ends; });
    if (it == around.end()) throw std::logic_error("tracking_mesh: an edge of the table is not in the edge graph");
    out[e] = *it;
  }
  return out;
}

// A tracker of one variant on one mesh, with what the comparison keeps between frames.
struct MeshTrack {
  SilhouetteTracker tracker;
  std::vector<std::uint32_t> missing_for;  // per graph edge: consecutive frames missed so far
  std::vector<std::uint8_t> on_list;       // scratch: 1 for the edges of this frame's list
};

}  // namespace

TrackingMesh tracking_mesh(std::string name, const Soup& soup) {
  require_indices_in_range(soup, "tracking_mesh");
  require_finite_vertices(soup, "tracking_mesh");
  TrackingMesh mesh;
  mesh.name = std::move(name);
  mesh.triangles = soup.triangles.size();
  mesh.canonical = canonical_soup(soup).soup;
  mesh.table = build_edge_table(mesh.canonical);
  const SmoothCasterResult caster = smooth_caster(soup);
  mesh.qualification = caster.qualification.summary();
  if (!caster.caster) return mesh;
  mesh.graph = silhouette_edge_graph(*caster.caster);
  mesh.graph_edge = graph_edges_of_table(mesh.canonical, mesh.table, *mesh.graph);
  return mesh;
}

TrackingSummary VariantTracking::summary() const {
  TrackingSummary s;
  s.frames = frames.size();
  if (frames.empty()) return s;
  for (const TrackingFrameRecord& f : frames) {
    const double rate = f.miss_rate();
    s.mean_miss_rate += rate;
    s.max_miss_rate = std::max(s.max_miss_rate, rate);
    s.frames_with_misses += f.missed > 0 ? 1 : 0;
    s.missed += f.missed;
    s.false_positives += f.false_positives;
    s.oldest_miss = std::max(s.oldest_miss, f.oldest_miss);
    s.mean_edges_checked += static_cast<double>(f.edges_checked);
    s.mean_found += static_cast<double>(f.found);
    s.mean_exact += static_cast<double>(f.exact);
    s.mean_milliseconds += f.milliseconds;
  }
  const auto n = static_cast<double>(frames.size());
  s.mean_miss_rate /= n;
  s.mean_edges_checked /= n;
  s.mean_found /= n;
  s.mean_exact /= n;
  s.mean_milliseconds /= n;
  return s;
}

TrackingComparison compare_tracking(std::span<const TrackingMesh> meshes, std::span<const Light> lights,
                                    std::span<const TrackingVariant> variants) {
  for (std::size_t i = 0; i < lights.size(); ++i)
    if (!lights[i].defined())
      throw std::invalid_argument("compare_tracking: light " + std::to_string(i) + " is not a defined light");
  for (const TrackingVariant& v : variants)
    if (v.search == TrackingSearch::periodic && v.period == 0)
      throw std::invalid_argument("compare_tracking: periodic tracking needs a period of at least 1");

  TrackingComparison out;
  std::vector<std::vector<MeshTrack>> tracks(variants.size());
  for (std::size_t v = 0; v < variants.size(); ++v) {
    out.variants.push_back({variants[v], {}});
    out.variants.back().frames.reserve(lights.size());
    for (const TrackingMesh& m : meshes)
      if (m.tracked())
        tracks[v].push_back({SilhouetteTracker(*m.graph, variants[v]), std::vector<std::uint32_t>(m.graph->edge_count(), 0),
                             std::vector<std::uint8_t>(m.graph->edge_count(), 0)});
  }
  std::vector<std::vector<std::uint8_t>> exact_edge;  // per tracked mesh, per graph edge: m != 0
  for (const TrackingMesh& m : meshes)
    if (m.tracked()) exact_edge.emplace_back(m.graph->edge_count(), 0);

  out.exact.reserve(lights.size());
  for (const Light& light : lights) {
    ExactSearchFrame exact;
    std::size_t k = 0;
    for (const TrackingMesh& m : meshes) {
      const Clock::time_point start = Clock::now();
      const EdgeMultiplicities em = exact_multiplicities(m.canonical, m.table, light);
      const double ms = milliseconds_since(start);
      const auto silhouette = static_cast<std::size_t>(
          std::count_if(em.multiplicity.begin(), em.multiplicity.end(), [](std::int32_t x) { return x != 0; }));
      if (!m.tracked()) {
        exact.fallback_milliseconds += ms;
        exact.fallback_edges += silhouette;
        continue;
      }
      exact.tracked_milliseconds += ms;
      exact.tracked_edges += silhouette;
      for (std::size_t e = 0; e < em.multiplicity.size(); ++e) exact_edge[k][m.graph_edge[e]] = em.multiplicity[e] != 0;
      ++k;
    }
    out.exact.push_back(exact);

    for (std::size_t v = 0; v < variants.size(); ++v) {
      TrackingFrameRecord record;
      record.full_search = !tracks[v].empty();
      for (std::size_t t = 0; t < tracks[v].size(); ++t) {
        MeshTrack& track = tracks[v][t];
        const std::vector<std::uint8_t>& is_exact = exact_edge[t];
        const Clock::time_point start = Clock::now();
        const TrackedFrame& frame = track.tracker.track(light);
        record.milliseconds += milliseconds_since(start);
        record.edges_checked += frame.edges_checked;
        record.faces_evaluated += frame.faces_evaluated;
        record.full_search = record.full_search && frame.full_search;
        record.found += frame.edges.size();
        for (const std::uint32_t e : frame.edges) {
          track.on_list[e] = 1;
          record.false_positives += is_exact[e] ? 0 : 1;
        }
        for (std::size_t e = 0; e < is_exact.size(); ++e) {
          if (is_exact[e] == 0 || track.on_list[e] != 0) {
            track.missing_for[e] = 0;
            record.exact += is_exact[e];
            continue;
          }
          ++record.exact;
          ++record.missed;
          record.oldest_miss = std::max(record.oldest_miss, ++track.missing_for[e]);
        }
        for (const std::uint32_t e : frame.edges) track.on_list[e] = 0;
      }
      out.variants[v].frames.push_back(record);
    }
  }
  return out;
}

}  // namespace shadowcert
