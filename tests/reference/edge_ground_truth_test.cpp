// The exact edge ground truth (reference/edge_ground_truth.h): a cube's outline and its visible
// creases, against an independent double-precision hidden-line sampler on scenes with
// occlusion, an edge exactly on the boundary between two pixel columns (excluded, never an
// edge), the footprint check against the exact image, grazing pixels, invariance under vertex
// relabelling, face reversal and an exact translation, and input validation.
#include "reference/edge_ground_truth.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "core/pixel_ray.h"
#include "core/vector3.h"
#include "exact/view_edges.h"
#include "reference/exact_image.h"
#include "scene/canonical_soup.h"
#include "scene/edge_table.h"
#include "scene/procedural_mesh.h"
#include "support/certificate_test_support.h"

namespace {

using namespace shadowcert;
using test_support::append;

std::size_t count(const std::vector<EdgeTruth>& v, EdgeTruth t) {
  return static_cast<std::size_t>(std::count(v.begin(), v.end(), t));
}

Camera make_camera(const Vec3& eye, const Vec3& target, std::uint32_t w, std::uint32_t h) {
  Camera c;
  c.eye = eye;
  c.target = target;
  c.width = w;
  c.height = h;
  return c;
}

// Two boxes, the nearer hiding part of the farther, a fan and a lone triangle over a floor.
Soup occlusion_scene() {
  Soup soup = floor_quad(4.0);
  append(soup, box({-1.0, 0.0, -1.0}, {0.5, 1.25, 0.5}));
  append(soup, box({0.0, 0.25, 1.0}, {1.0, 1.0, 1.75}));
  // A fan of five blades on one edge (a non-manifold silhouette), every coordinate on a grid
  // of 1/64 so that a translation by 8 is exact.
  Soup fan;
  fan.vertices = {{-2.0, 0.0, 1.0},  {-2.0, 1.5, 1.0},  {-1.25, 0.75, 1.0}, {-2.0, 0.75, 1.75},
                  {-2.75, 0.75, 1.0}, {-2.0, 0.75, 0.25}, {-1.5, 0.75, 1.5}};
  for (std::uint32_t k = 2; k < 7; ++k) fan.triangles.push_back(k % 2 == 0 ? Triangle{0, 1, k} : Triangle{1, 0, k});
  append(soup, fan);
  Soup lone;
  lone.vertices = {{1.5, 0.5, -1.5}, {2.5, 0.75, -1.0}, {1.75, 1.5, -0.5}};
  lone.triangles = {{0, 1, 2}};
  append(soup, lone);
  return soup;
}

TEST(EdgeGroundTruth, CubeOutlineAndVisibleCreases) {
  const Soup cube = box({0.0, 0.0, 0.0}, {1.0, 1.0, 1.0});
  EdgeGroundTruthOptions options;
  options.check_footprints = true;
  const EdgeGroundTruth truth = edge_ground_truth(cube, make_camera({3.0, 2.5, 3.5}, {0.5, 0.5, 0.5}, 96, 72), options);
  EXPECT_EQ(truth.stats.profile_edges, 6u);
  EXPECT_EQ(truth.stats.inner_edges, 6u);
  EXPECT_EQ(truth.stats.visible_profile_edges, 6u);
  EXPECT_EQ(truth.stats.visible_inner_edges, 3u);  // the three at the far corner are hidden
  EXPECT_GT(count(truth.profile, EdgeTruth::edge), 100u);
  EXPECT_GT(count(truth.inner, EdgeTruth::edge), 50u);
  EXPECT_EQ(truth.stats.unseen_edge_pixels, 0u);
  // Creases lie inside the outline: a crease pixel's centre sees the cube, but where the
  // crease ends on the outline, a neighbour's does.
  for (std::uint32_t r = 1; r + 1 < truth.height; ++r)
    for (std::uint32_t i = 1; i + 1 < truth.width; ++i) {
      if (truth.inner[std::size_t{r} * truth.width + i] != EdgeTruth::edge) continue;
      bool sees = false;
      for (std::uint32_t y = r - 1; y <= r + 1; ++y)
        for (std::uint32_t x = i - 1; x <= i + 1; ++x) sees |= truth.hit_triangles[std::size_t{y} * truth.width + x] != kNoHit;
      EXPECT_TRUE(sees) << i << ", " << r;
    }
}

// --- an independent check: sampled hidden lines in double ----------------------------------

struct Sampled {
  std::size_t visible_samples = 0;
  std::size_t misplaced = 0;        // a visible sample in a pixel the truth calls none
  std::size_t edge_pixels = 0;
  std::size_t edge_pixels_without_sample = 0;
};

// Whether the segment eye -> x meets triangle abc before x, in double (Moller-Trumbore), and
// whether that is too close to call (`unsure`).
bool hides(const Vec3& eye, const Vec3& x, const Vec3& a, const Vec3& b, const Vec3& c, bool& unsure) {
  const Vec3 d = difference(x, eye), e1 = difference(b, a), e2 = difference(c, a);
  const Vec3 p = cross(d, e2);
  const double det = dot(e1, p);
  if (std::abs(det) < 1e-14) return false;
  const Vec3 s = difference(eye, a);
  const double bu = dot(s, p) / det;
  const Vec3 q = cross(s, e1);
  const double bv = dot(d, q) / det, t = dot(e2, q) / det;
  constexpr double kTol = 1e-7;
  const bool inside = bu > -kTol && bv > -kTol && bu + bv < 1 + kTol && t > -kTol && t < 1 + kTol;
  if (!inside) return false;
  const bool clearly = bu > kTol && bv > kTol && bu + bv < 1 - kTol && t > kTol && t < 1 - kTol;
  if (!clearly) unsure = true;
  return clearly;
}

Sampled sample_hidden_lines(const Soup& soup, const Camera& camera, const EdgeGroundTruth& truth, bool inner_class) {
  const CameraFrame f = camera_frame(camera);
  const Soup s = canonical_soup(soup).soup;
  const EdgeTable table = build_edge_table(s);
  const ViewEdges classes = view_edges(s, table, camera.eye, std::cos(30.0 * 3.14159265358979323846 / 180.0));
  const std::uint8_t wanted = inner_class ? kInnerEdges : kProfileEdges;
  const std::vector<EdgeTruth>& t = inner_class ? truth.inner : truth.profile;
  std::vector<std::uint8_t> sampled(t.size(), 0);
  Sampled out;
  for (std::size_t e = 0; e < table.size(); ++e) {
    if ((classes.classes[e] & wanted) == 0) continue;
    const std::uint32_t iu = table.edges[e][0], iv = table.edges[e][1];
    const Vec3 &u = s.vertices[iu], &v = s.vertices[iv];
    constexpr int kSamples = 4000;
    for (int k = 1; k < kSamples; ++k) {
      const double w = static_cast<double>(k) / kSamples;
      const Vec3 x{u[0] + w * (v[0] - u[0]), u[1] + w * (v[1] - u[1]), u[2] + w * (v[2] - u[2])};
      bool unsure = false, hidden = false;
      for (const Triangle& tri : s.triangles) {
        const bool has_u = tri[0] == iu || tri[1] == iu || tri[2] == iu, has_v = tri[0] == iv || tri[1] == iv || tri[2] == iv;
        if (has_u && has_v) continue;
        if (hides(camera.eye, x, s.vertices[tri[0]], s.vertices[tri[1]], s.vertices[tri[2]], unsure)) {
          hidden = true;
          break;
        }
      }
      if (hidden || unsure) continue;
      const Vec3 d = difference(x, f.eye);
      const double xc = dot(d, f.right), yc = dot(d, f.up), zc = dot(d, f.forward);
      if (zc <= 0) continue;
      const double px = 0.5 * f.width * (1 + xc / (zc * f.half_width)), py = 0.5 * f.height * (1 - yc / (zc * f.half_height));
      if (px < 0 || py < 0 || px >= f.width || py >= f.height) continue;
      const double fx = px - std::floor(px), fy = py - std::floor(py);
      if (fx < 1e-6 || fx > 1 - 1e-6 || fy < 1e-6 || fy > 1 - 1e-6) continue;  // on a pixel boundary
      const std::size_t p = static_cast<std::size_t>(py) * f.width + static_cast<std::size_t>(px);
      ++out.visible_samples;
      sampled[p] = 1;
      if (t[p] != EdgeTruth::edge) ++out.misplaced;
    }
  }
  for (std::size_t p = 0; p < t.size(); ++p) {
    if (t[p] != EdgeTruth::edge) continue;
    ++out.edge_pixels;
    if (sampled[p] == 0) ++out.edge_pixels_without_sample;
  }
  return out;
}

TEST(EdgeGroundTruth, AgreesWithSampledHiddenLines) {
  const Soup soup = occlusion_scene();
  for (const Camera& camera : {make_camera({4.0, 3.0, 6.0}, {0.0, 0.5, 0.0}, 80, 60),
                               make_camera({-5.0, 1.5, 3.0}, {0.25, 0.75, 0.0}, 96, 64)}) {
    EdgeGroundTruthOptions options;
    options.check_footprints = true;
    const EdgeGroundTruth truth = edge_ground_truth(soup, camera, options);
    EXPECT_EQ(truth.stats.unseen_edge_pixels, 0u);
    for (const bool inner : {false, true}) {
      const Sampled s = sample_hidden_lines(soup, camera, truth, inner);
      SCOPED_TRACE(inner ? "inner" : "profile");
      EXPECT_GT(s.visible_samples, 1000u);
      EXPECT_EQ(s.misplaced, 0u);
      // Every edge pixel holds a visible sample but those where the visible piece only clips
      // a corner of the pixel (a few per cent at most).
      EXPECT_LE(s.edge_pixels_without_sample * 20, s.edge_pixels) << s.edge_pixels_without_sample << " of " << s.edge_pixels;
    }
    // Hidden edges leave no trace: the far box's creases behind the near box are partly hidden.
    EXPECT_LT(truth.stats.visible_inner_edges, truth.stats.inner_edges);
  }
}

TEST(EdgeGroundTruth, EdgeOnAPixelBoundaryIsExcluded) {
  // The eye at the origin looking down -z: the centre column's corner rays are (0, b, -1)
  // exactly, so a triangle's edge in the plane x = 0 lies on the face shared by the columns
  // W/2 - 1 and W/2 along its whole length: it touches both, passes through neither.
  Soup soup;
  soup.vertices = {{0.0, -1.0, -5.0}, {0.0, 1.0, -5.0}, {1.5, 0.0, -5.0}};
  soup.triangles = {{0, 1, 2}};
  const Camera camera = make_camera({0.0, 0.0, 0.0}, {0.0, 0.0, -1.0}, 64, 48);
  const EdgeGroundTruth truth = edge_ground_truth(soup, camera);
  const std::uint32_t left = 31, right = 32, middle = 24;
  std::size_t excluded = 0;
  for (std::uint32_t r = 0; r < 48; ++r) {
    const EdgeTruth t = truth.profile[std::size_t{r} * 64 + left];
    EXPECT_NE(t, EdgeTruth::edge) << r;
    excluded += t == EdgeTruth::excluded;
  }
  EXPECT_GT(excluded, 10u);
  EXPECT_EQ(truth.profile[std::size_t{middle} * 64 + left], EdgeTruth::excluded);
  EXPECT_EQ(truth.profile[std::size_t{middle} * 64 + right], EdgeTruth::excluded);
  // The slanted edges pass through pixels right of the line.
  EXPECT_GT(count(truth.profile, EdgeTruth::edge), 20u);
}

TEST(EdgeGroundTruth, GrazingPixelsOnAFloor) {
  Soup soup = floor_quad(50.0);
  const Camera camera = make_camera({0.0, 1.0, 10.0}, {0.0, 0.0, 0.0}, 64, 96);
  const EdgeGroundTruth truth = edge_ground_truth(soup, camera);
  const CameraFrame f = camera_frame(camera);
  std::size_t grazing = 0, checked = 0;
  for (std::uint32_t r = 0; r < camera.height; ++r)
    for (std::uint32_t i = 0; i < camera.width; ++i) {
      const std::size_t p = std::size_t{r} * camera.width + i;
      if (truth.hit_triangles[p] == kNoHit) {
        EXPECT_EQ(truth.grazing[p], 0);
        continue;
      }
      const PixelRay ray = pixel_ray(f, i + 0.5, r + 0.5);
      const double incidence = std::acos(std::abs(ray.direction[1]) / std::sqrt(dot(ray.direction, ray.direction))) *
                               180.0 / 3.14159265358979323846;
      if (std::abs(incidence - 80.0) < 0.01) continue;
      ++checked;
      EXPECT_EQ(truth.grazing[p] != 0, incidence > 80.0) << i << ", " << r;
      grazing += truth.grazing[p];
    }
  EXPECT_GT(grazing, 100u);
  EXPECT_LT(grazing, checked);
}

EdgeGroundTruth truth_of(const Soup& soup, const Camera& camera) { return edge_ground_truth(soup, camera); }

TEST(EdgeGroundTruth, InvariantUnderRelabellingReversalAndTranslation) {
  Soup soup = occlusion_scene();
  append(soup, uv_sphere({-1.5, 0.75, -2.0}, 0.5, 10, 6));
  soup.normals.clear();
  const Camera camera = make_camera({4.0, 3.0, 6.0}, {0.0, 0.5, 0.0}, 72, 54);
  const EdgeGroundTruth reference = truth_of(soup, camera);
  EXPECT_GT(count(reference.profile, EdgeTruth::edge), 0u);
  EXPECT_GT(count(reference.inner, EdgeTruth::edge), 0u);

  std::mt19937_64 random(15);
  std::vector<std::uint32_t> order(soup.vertices.size());
  for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
  std::shuffle(order.begin(), order.end(), random);
  Soup relabelled;
  relabelled.vertices.resize(soup.vertices.size());
  for (std::size_t i = 0; i < order.size(); ++i) relabelled.vertices[order[i]] = soup.vertices[i];
  for (const Triangle& t : soup.triangles) relabelled.triangles.push_back({order[t[0]], order[t[1]], order[t[2]]});
  const EdgeGroundTruth r = truth_of(relabelled, camera);
  EXPECT_EQ(r.profile, reference.profile);
  EXPECT_EQ(r.inner, reference.inner);

  Soup reversed = soup;
  for (Triangle& t : reversed.triangles) std::swap(t[1], t[2]);
  const EdgeGroundTruth f = truth_of(reversed, camera);
  EXPECT_EQ(f.profile, reference.profile);
  EXPECT_EQ(f.inner, reference.inner);
  EXPECT_EQ(f.grazing, reference.grazing);
}

TEST(EdgeGroundTruth, InvariantUnderExactTranslation) {
  // Coordinates on a grid of 1/64, moved by 8: every difference stays the same double.
  const Soup soup = occlusion_scene();
  const Camera camera = make_camera({4.0, 3.0, 6.0}, {0.0, 0.5, 0.0}, 64, 48);
  const EdgeGroundTruth reference = truth_of(soup, camera);
  Soup moved = soup;
  for (Vec3& p : moved.vertices) p = {p[0] + 8.0, p[1] - 8.0, p[2] + 16.0};
  Camera moved_camera = camera;
  moved_camera.eye = {12.0, -5.0, 22.0};
  moved_camera.target = {8.0, -7.5, 16.0};
  const EdgeGroundTruth m = truth_of(moved, moved_camera);
  EXPECT_EQ(m.profile, reference.profile);
  EXPECT_EQ(m.inner, reference.inner);
}

TEST(EdgeGroundTruth, EmptySoupHasNoEdge) {
  const EdgeGroundTruth truth = edge_ground_truth(Soup{}, make_camera({3.0, 2.5, 3.5}, {0.5, 0.5, 0.5}, 16, 12));
  EXPECT_EQ(count(truth.profile, EdgeTruth::none), 16u * 12u);
  EXPECT_EQ(count(truth.inner, EdgeTruth::none), 16u * 12u);
  EXPECT_EQ(std::count(truth.hit_triangles.begin(), truth.hit_triangles.end(), kNoHit), 16 * 12);
}

TEST(EdgeGroundTruth, RejectsBadInput) {
  const Soup cube = box({0.0, 0.0, 0.0}, {1.0, 1.0, 1.0});
  const Camera camera = make_camera({3.0, 2.5, 3.5}, {0.5, 0.5, 0.5}, 16, 12);
  EdgeGroundTruthOptions bad;
  bad.crease_degrees = 200.0;
  EXPECT_THROW((void)edge_ground_truth(cube, camera, bad), std::invalid_argument);
  Soup broken = cube;
  broken.triangles.push_back({0, 1, 99});
  EXPECT_THROW((void)edge_ground_truth(broken, camera), std::invalid_argument);
  Camera degenerate = camera;
  degenerate.target = degenerate.eye;
  EXPECT_THROW((void)edge_ground_truth(cube, degenerate), std::invalid_argument);
}

}  // namespace
