// The GL edge maps against the exact ground truth (pipeline/edge_map_comparison.h): the truth
// itself fed in as an edge map scores exactly 1 for every class and tolerance; the class images
// (the union class any); every filter on a box over a floor finds the box's outline and creases
// at its best threshold; the pictures have the frame's size.
#include "pipeline/edge_map_comparison.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>

#include "core/scene.h"
#include "pipeline/edge_map_pictures.h"
#include "reference/exact_image.h"
#include "scene/framed_scene.h"
#include "scene/procedural_mesh.h"
#include "support/gl_test_support.h"

namespace shadowcert {
namespace {

using gpu::test::GlTest;

Scene box_scene(std::uint32_t w, std::uint32_t h) {
  FramedMeshOptions options;
  options.width = w;
  options.height = h;
  return framed_mesh_scene(box({0.0, 0.0, 0.0}, {1.0, 0.75, 1.25}), "box", options);
}

// The truth as an edge map: intensity 1 on truth pixels of each class.
gpu::EdgeMapImage truth_as_map(const EdgeGroundTruth& truth) {
  gpu::EdgeMapImage map;
  map.width = truth.width;
  map.height = truth.height;
  for (std::size_t p = 0; p < truth.profile.size(); ++p) {
    map.profile.push_back(truth.profile[p] == EdgeTruth::edge ? 1.0f : 0.0f);
    map.inner.push_back(truth.inner[p] == EdgeTruth::edge ? 1.0f : 0.0f);
    map.covered.push_back(truth.hit_triangles[p] != kNoHit ? 1 : 0);
  }
  return map;
}

TEST(EdgeMapComparison, TheTruthScoresOne) {
  const EdgeGroundTruth truth = scene_edge_ground_truth(box_scene(128, 96));
  const std::vector<double> thresholds = default_edge_thresholds();
  const std::vector<EdgeTolerance> tolerances{{EdgeMatching::window, 0, 0.0075}, {EdgeMatching::window, 1, 0.0075},
                                              {EdgeMatching::window, 2, 0.0075}, {EdgeMatching::bsds, 0, 0.0075}};
  const EdgeFilterRun run = score_edge_map(truth, truth_as_map(truth), gpu::EdgeFilter::diagonal, thresholds, tolerances);
  for (const EdgeClass c : kEdgeClasses)
    for (std::size_t k = 0; k < tolerances.size(); ++k)
      for (const EdgeMatchCounts& m : run.curve(c, k)) {
        EXPECT_GT(m.truth, 0u);
        EXPECT_EQ(m.f1(), 1.0) << edge_class_name(c) << " " << tolerances[k].name();
      }
  gpu::EdgeMapImage small;
  small.width = 3;
  small.height = 2;
  EXPECT_THROW((void)score_edge_map(truth, small, gpu::EdgeFilter::c1, thresholds, tolerances), std::invalid_argument);
}

TEST(EdgeMapComparison, AnyClassIsTheUnion) {
  EdgeGroundTruth truth;
  truth.width = 4;
  truth.height = 1;
  truth.profile = {EdgeTruth::edge, EdgeTruth::none, EdgeTruth::excluded, EdgeTruth::none};
  truth.inner = {EdgeTruth::none, EdgeTruth::edge, EdgeTruth::edge, EdgeTruth::none};
  gpu::EdgeMapImage map;
  map.width = 4;
  map.height = 1;
  map.profile = {0.5f, 0.1f, 0.0f, 0.2f};
  map.inner = {0.25f, 0.75f, 0.0f, 0.3f};
  const EdgeClassImages any = edge_class_images(truth, map, EdgeClass::any);
  EXPECT_EQ(any.truth, (std::vector<EdgeTruth>{EdgeTruth::edge, EdgeTruth::edge, EdgeTruth::edge, EdgeTruth::none}));
  EXPECT_EQ(any.intensity, (std::vector<float>{0.5f, 0.75f, 0.0f, 0.3f}));
  const EdgeClassImages inner = edge_class_images(truth, map, EdgeClass::inner);
  EXPECT_EQ(inner.truth, truth.inner);
  EXPECT_EQ(inner.intensity, map.inner);
  EXPECT_EQ(edge_class_name(EdgeClass::any), "any");
}

class EdgeMapComparisonGl : public GlTest {};

TEST_F(EdgeMapComparisonGl, EveryFilterFindsTheBox) {
  const Scene scene = box_scene(160, 120);
  EdgeMapComparisonOptions options;
  options.timed_frames = 1;
  const EdgeMapComparison c = compare_edge_maps(scene, options);
  ASSERT_EQ(c.runs.size(), gpu::kEdgeFilters.size());
  EXPECT_GT(c.truth.stats.visible_inner_edges, 0u);
  for (const EdgeFilterRun& run : c.runs) {
    SCOPED_TRACE(std::string(gpu::edge_filter_name(run.filter)));
    EXPECT_EQ(run.map.width, 160u);
    for (const EdgeClass k : kEdgeClasses) {
      const std::vector<EdgeMatchCounts>& curve = run.curve(k, 0);  // 1 px
      const EdgeMatchCounts& best = curve[best_threshold_of(curve)];
      EXPECT_GT(best.f1(), k == EdgeClass::any ? 0.9 : 0.6) << edge_class_name(k);
    }
    EXPECT_EQ(run.times.frames, 1u);
    const std::vector<EdgeVerdict> verdicts = edge_verdicts(
        {c.truth.width, c.truth.height, c.truth.profile, c.truth.grazing, run.map.profile}, 1, 0.05);
    const gpu::RgbaImage picture = edge_verdict_picture(c.truth, verdicts);
    EXPECT_EQ(picture.width, 160u);
    EXPECT_EQ(picture.pixels.size(), 160u * 120u * 4u);
  }
  EXPECT_EQ(edge_truth_picture(c.truth).height, 120u);
  // What diff shows: a row per filter and class at the measured thresholds, and the pictures.
  const std::vector<EdgeScoreRow> rows = edge_score_rows(c);
  ASSERT_EQ(rows.size(), gpu::kEdgeFilters.size() * kEdgeClasses.size());
  for (const EdgeScoreRow& row : rows) {
    EXPECT_EQ(row.threshold, measured_edge_threshold(row.filter, row.edge_class));
    EXPECT_EQ(row.counts.size(), c.tolerances.size());
  }
  const std::vector<NamedEdgePicture> pictures = edge_map_pictures(c);
  EXPECT_EQ(pictures.size(), 1 + gpu::kEdgeFilters.size() * (2 + kEdgeClasses.size()));
  EXPECT_EQ(pictures.front().name, "edge_truth");
  for (const NamedEdgePicture& p : pictures) EXPECT_EQ(p.image.width, 160u) << p.name;
  EXPECT_THROW((void)compare_edge_maps(scene, EdgeMapComparisonOptions{{}, {0.5}, {EdgeTolerance{}}}),
               std::invalid_argument);
}

}  // namespace
}  // namespace shadowcert
