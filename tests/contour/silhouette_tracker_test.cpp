// contour/silhouette_tracker.h: the variants of Chen and Tsai's silhouette tracking held to the
// full search (every edge tested) frame by frame: continue finds every silhouette edge along the
// orbits of concave meshes, one-way misses the branches of a bifurcation (the paper's Figure 4,
// built here on a coarse torus) but nothing on a convex sphere, periodic:T never lets an edge
// stay missing T frames, and tracking tests a small part of the edges.
#include "contour/silhouette_tracker.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "scene/light_orbit.h"
#include "scene/procedural_mesh.h"
#include "support/contour_test_support.h"

namespace {

using namespace shadowcert;
using test_support::caster_of;

const TrackingVariant kFull{TrackingSearch::full, 0};
const TrackingVariant kOneWay{TrackingSearch::one_way, 0};
const TrackingVariant kContinue{TrackingSearch::continue_search, 0};

SilhouetteEdgeGraph graph_of(const Soup& soup) { return silhouette_edge_graph(caster_of(soup)); }

std::vector<Light> orbit(double radius, double height, std::size_t frames) {
  return orbit_lights(LightOrbit{{0, 0, 0}, radius, height, 1.0}, frames);
}

std::set<std::uint32_t> as_set(const std::vector<std::uint32_t>& edges) { return {edges.begin(), edges.end()}; }

// Every edge tested, by the definition (contour/silhouette_edge_graph.h).
std::set<std::uint32_t> brute_force(const SilhouetteEdgeGraph& g, const Light& light) {
  std::set<std::uint32_t> out;
  for (std::uint32_t e = 0; e < g.edge_count(); ++e) {
    const auto [f0, f1] = g.edge_faces[e];
    const bool border = f1 == kBorder;
    if (silhouette_sides(face_light_side(g, f0, light), border ? Sign::zero : face_light_side(g, f1, light), border))
      out.insert(e);
  }
  return out;
}

// The silhouette edges connected to `edge` through shared vertices, and whether a vertex among
// them has more than two silhouette edges (a bifurcation).
bool component_bifurcates(const SilhouetteEdgeGraph& g, const std::set<std::uint32_t>& silhouette, std::uint32_t edge) {
  std::set<std::uint32_t> seen{edge};
  std::vector<std::uint32_t> stack{edge};
  bool bifurcates = false;
  while (!stack.empty()) {
    const std::uint32_t e = stack.back();
    stack.pop_back();
    for (const std::uint32_t v : g.edge_vertices[e]) {
      std::size_t at_v = 0;
      for (const std::uint32_t n : g.edges_at(v))
        if (silhouette.count(n)) {
          ++at_v;
          if (seen.insert(n).second) stack.push_back(n);
        }
      bifurcates = bifurcates || at_v > 2;
    }
  }
  return bifurcates;
}

TEST(SilhouetteTracker, Full_TestsEveryEdgeAndFindsTheDefinitionsEdges) {
  const SilhouetteEdgeGraph g = graph_of(torus_knot({0, 0, 0}, 2, 3, 1.0, 0.4, 0.12, 64, 8));
  SilhouetteTracker full(g, kFull);
  for (const Light& light : orbit(3.0, 0.6, 24)) {
    const TrackedFrame& f = full.track(light);
    EXPECT_TRUE(f.full_search);
    EXPECT_EQ(f.edges_checked, g.edge_count());
    EXPECT_EQ(f.faces_evaluated, g.face_count());
    EXPECT_EQ(as_set(f.edges), brute_force(g, light));
    EXPECT_EQ(as_set(f.edges).size(), f.edges.size());  // no edge twice
  }
}

// The paper's §5 fix: searching on through found edges reaches every silhouette edge connected
// to a survivor or to a concave or border edge, which on these orbits is every one.
TEST(SilhouetteTracker, Continue_FindsEverySilhouetteEdgeOnEveryFrameOfConcaveOrbits) {
  const std::vector<std::pair<std::string, Soup>> meshes{
      {"torus 8x8", torus({0, 0, 0}, 1.0, 0.3, 8, 8)},
      {"torus 48x24", torus({0, 0, 0}, 1.0, 0.25, 48, 24)},
      {"knot 128x12", torus_knot({0, 0, 0}, 2, 3, 1.0, 0.4, 0.12, 128, 12)}};
  for (const auto& [name, soup] : meshes) {
    const SilhouetteEdgeGraph g = graph_of(soup);
    ASSERT_FALSE(g.concave_edges.empty()) << name;
    for (const double radius : {2.0, 3.0})
      for (const double height : {0.0, 0.6, -1.0})
        for (const std::size_t frames : {36u, 180u}) {
          SilhouetteTracker tracker(g, kContinue);
          const std::vector<Light> lights = orbit(radius, height, frames);
          for (std::size_t i = 0; i < lights.size(); ++i) {
            const TrackedFrame& f = tracker.track(lights[i]);
            EXPECT_EQ(f.full_search, i == 0);
            EXPECT_EQ(as_set(f.edges), brute_force(g, lights[i]))
                << name << " radius " << radius << " height " << height << " frames " << frames << " frame " << i;
          }
        }
  }
}

// The paper: one-way search misses nothing on a convex model (one silhouette loop, no
// bifurcation).
TEST(SilhouetteTracker, OneWay_ConvexSphere_MissesNothing) {
  const SilhouetteEdgeGraph g = graph_of(uv_sphere({0, 0, 0}, 1.0, 64, 32));
  for (const double height : {0.0, 1.5})
    for (const std::size_t frames : {36u, 360u}) {
      SilhouetteTracker tracker(g, kOneWay);
      for (const Light& light : orbit(3.0, height, frames))
        ASSERT_EQ(as_set(tracker.track(light).edges), brute_force(g, light)) << "height " << height << " frames " << frames;
    }
}

// The paper's Figure 4, built: a torus of 8 x 8 segments (minor radius 0.3) lit from its own
// plane, the light 10 degrees along an orbit of radius 3 from the first frame. On the inner side
// two silhouette chains meet at vertices with four silhouette edges each. The one-way walk that
// enters the new branch there stops at once (the edge it stepped to touches the silhouette edges
// already found at that vertex), so the rest of the branch is missed; continue finds it.
TEST(SilhouetteTracker, OneWay_BifurcationCase_MissesWhatContinueFinds) {
  const SilhouetteEdgeGraph g = graph_of(torus({0, 0, 0}, 1.0, 0.3, 8, 8));
  const std::vector<Light> lights = orbit(3.0, 0.0, 36);
  SilhouetteTracker one_way(g, kOneWay), continued(g, kContinue);
  (void)one_way.track(lights[0]);
  (void)continued.track(lights[0]);
  const std::set<std::uint32_t> truth = brute_force(g, lights[1]);
  const std::set<std::uint32_t> walked = as_set(one_way.track(lights[1]).edges);
  EXPECT_EQ(as_set(continued.track(lights[1]).edges), truth);
  std::size_t missed = 0;
  for (const std::uint32_t e : truth) {
    if (walked.count(e)) continue;
    ++missed;
    EXPECT_TRUE(component_bifurcates(g, truth, e)) << "missed edge " << e << " is on no bifurcating chain";
  }
  EXPECT_EQ(missed, 2u);
  for (const std::uint32_t e : walked) EXPECT_TRUE(truth.count(e)) << "edge " << e << " is not a silhouette edge";
}

// One-way's misses last several frames on a knot whose tube the light grazes; periodic:T's full
// search on every T-th frame bounds how long any edge stays missing.
TEST(SilhouetteTracker, Periodic_NoEdgeStaysMissingForTFrames) {
  const SilhouetteEdgeGraph g = graph_of(torus_knot({0, 0, 0}, 2, 3, 1.0, 0.4, 0.12, 64, 8));
  const std::vector<Light> lights = orbit(1.5, 0.0, 180);
  const auto oldest_miss = [&](const TrackingVariant& variant) {
    SilhouetteTracker tracker(g, variant);
    std::map<std::uint32_t, std::uint32_t> missing_for;
    std::uint32_t oldest = 0;
    for (std::size_t i = 0; i < lights.size(); ++i) {
      const TrackedFrame& f = tracker.track(lights[i]);
      if (variant.search == TrackingSearch::periodic) {
        EXPECT_EQ(f.full_search, i % variant.period == 0) << "frame " << i;
      }
      const std::set<std::uint32_t> found = as_set(f.edges);
      const std::set<std::uint32_t> truth = brute_force(g, lights[i]);
      std::map<std::uint32_t, std::uint32_t> next;
      for (const std::uint32_t e : truth) {
        if (!found.count(e)) oldest = std::max(oldest, next[e] = missing_for[e] + 1);
      }
      missing_for = std::move(next);
    }
    return oldest;
  };
  const std::uint32_t one_way = oldest_miss(kOneWay);
  EXPECT_GE(one_way, 4u);
  for (const std::uint32_t period : {1u, 2u, 3u, 4u}) {
    const std::uint32_t periodic = oldest_miss({TrackingSearch::periodic, period});
    EXPECT_LT(periodic, period) << "periodic:" << period;
  }
}

TEST(SilhouetteTracker, Tracking_TestsAFewPercentOfTheEdgesOfAFineSphere) {
  const SilhouetteEdgeGraph g = graph_of(uv_sphere({0, 0, 0}, 1.0, 200, 100));
  for (const TrackingVariant& variant : {kOneWay, kContinue}) {
    SilhouetteTracker tracker(g, variant);
    const std::vector<Light> lights = orbit(3.0, 0.8, 360);
    (void)tracker.track(lights[0]);
    for (std::size_t i = 1; i < 20; ++i) {
      const TrackedFrame& f = tracker.track(lights[i]);
      EXPECT_FALSE(f.full_search);
      EXPECT_LT(f.edges_checked, g.edge_count() / 20) << tracking_variant_name(variant) << " frame " << i;
      EXPECT_EQ(as_set(f.edges), brute_force(g, lights[i]));
    }
  }
}

// With no previous list, no concave and no border edge, the search starts from the first
// silhouette edge in index order (the paper's E0).
TEST(SilhouetteTracker, ResumeFromNothing_StartsAtTheFirstSilhouetteEdge) {
  const SilhouetteEdgeGraph g = graph_of(uv_sphere({0, 0, 0}, 1.0, 48, 24));
  const Light light{{0.3, 2.5, 1.2, 1.0}};
  for (const TrackingVariant& variant : {kOneWay, kContinue}) {
    SilhouetteTracker tracker(g, variant);
    tracker.resume_from({});
    const TrackedFrame& f = tracker.track(light);
    EXPECT_FALSE(f.full_search);
    EXPECT_EQ(as_set(f.edges), brute_force(g, light)) << tracking_variant_name(variant);
    EXPECT_EQ(f.edges.front(), *brute_force(g, light).begin());
  }
}

TEST(SilhouetteTracker, Misuse_Throws) {
  const SilhouetteEdgeGraph g = graph_of(box({0, 0, 0}, {1, 1, 1}));
  EXPECT_THROW(SilhouetteTracker(g, {TrackingSearch::periodic, 0}), std::invalid_argument);
  SilhouetteTracker tracker(g, kOneWay);
  EXPECT_THROW(tracker.resume_from({18}), std::invalid_argument);
  EXPECT_THROW((void)tracker.track(Light{{0, 0, 0, 0}}), std::invalid_argument);
  EXPECT_THROW((void)tracker.track(Light{{0, 1, 0, 2}}), std::invalid_argument);
}

TEST(TrackingVariant, Names_RoundTripAndBadOnesAreRefused) {
  for (const char* name : {"full", "one-way", "continue", "periodic:1", "periodic:10", "periodic:4294967295"}) {
    const auto v = parse_tracking_variant(name);
    ASSERT_TRUE(v) << name;
    EXPECT_EQ(tracking_variant_name(*v), name);
  }
  for (const char* name : {"", "one_way", "Full", "periodic", "periodic:", "periodic:0", "periodic:-1", "periodic:+3",
                           "periodic:3x", "periodic:4294967296", "all"})
    EXPECT_FALSE(parse_tracking_variant(name)) << name;
}

}  // namespace
