// edge_ground_truth of reference/edge_ground_truth.h:
//   1. classes: the canonical soup, its edge table and exact/view_edges.h's classes for the eye;
//   2. the exact image's centre hits (no light) and the grazing flags on them;
//   3. per profile or inner edge, in parallel: its hidden intervals (every triangle in the
//      pyramid from the eye over the edge, reference/detail/edge_visibility.h), its visible
//      pieces, the candidate pixels around their projection (double, a pixel's margin), and per
//      candidate the exact test against the pixel's eye pyramid;
//   4. per pixel: edge where some edge of the class passes, excluded where one only touches.
#include "reference/edge_ground_truth.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/box.h"
#include "core/pixel_ray.h"
#include "core/vector3.h"
#include "exact/box_tree.h"
#include "exact/light_orientation.h"
#include "exact/normal_angle.h"
#include "exact/view_edges.h"
#include "reference/detail/edge_visibility.h"
#include "reference/exact_image.h"
#include "scene/canonical_soup.h"
#include "scene/edge_table.h"

namespace shadowcert {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

double cosine_of(double degrees, const char* what) {
  try {
    return angle_cosine(degrees);
  } catch (const std::invalid_argument&) {
    throw std::invalid_argument(std::string("edge_ground_truth: ") + what + " must lie in [0, 180] degrees");
  }
}

// Marks per pixel: bit 0 a profile edge passes, bit 1 one touches; bits 2, 3 the same for inner.
constexpr std::uint8_t kPasses = 1;
constexpr std::uint8_t kTouches = 2;

// The pixels that may meet the segment a -> b (double points, approximately on the edge):
// those within about a pixel of its projection, clipped to the view enlarged by two pixels.
// Appends pixel indices (row * width + column) to `out`; a segment through the eye proposes
// every pixel. Candidates only: the exact test decides.
void candidate_pixels(const CameraFrame& f, const Vec3& a, const Vec3& b, std::vector<std::uint32_t>& out) {
  const auto camera = [&](const Vec3& x) {
    const Vec3 d = difference(x, f.eye);
    return Vec3{dot(d, f.right), dot(d, f.up), dot(d, f.forward)};
  };
  const Vec3 ca = camera(a), cb = camera(b);
  const double kx = f.half_width * (1.0 + 4.0 / f.width), ky = f.half_height * (1.0 + 4.0 / f.height);
  double t0 = 0.0, t1 = 1.0;
  const auto clip = [&](double fa, double fb) {
    if (fa < 0.0 && fb < 0.0) return false;
    if (fa < 0.0) t0 = std::max(t0, fa / (fa - fb));
    if (fb < 0.0) t1 = std::min(t1, fa / (fa - fb));
    return t0 <= t1;
  };
  if (!clip(kx * ca[2] - ca[0], kx * cb[2] - cb[0]) || !clip(kx * ca[2] + ca[0], kx * cb[2] + cb[0]) ||
      !clip(ky * ca[2] - ca[1], ky * cb[2] - cb[1]) || !clip(ky * ca[2] + ca[1], ky * cb[2] + cb[1]))
    return;
  const auto at = [&](double t) {
    return Vec3{ca[0] + t * (cb[0] - ca[0]), ca[1] + t * (cb[1] - ca[1]), ca[2] + t * (cb[2] - ca[2])};
  };
  const Vec3 p0 = at(t0), p1 = at(t1);
  const auto width = static_cast<std::int64_t>(f.width), height = static_cast<std::int64_t>(f.height);
  if (!(p0[2] > 0.0 && p1[2] > 0.0)) {  // through the eye: no projection
    for (std::uint32_t k = 0; k < f.width * f.height; ++k) out.push_back(k);
    return;
  }
  const auto project = [&](const Vec3& p) {
    return std::array<double, 2>{0.5 * f.width * (1.0 + p[0] / (p[2] * f.half_width)),
                                 0.5 * f.height * (1.0 - p[1] / (p[2] * f.half_height))};
  };
  const auto [x0, y0] = project(p0);
  const auto [x1, y1] = project(p1);
  constexpr double kMargin = 1.0;
  const auto first_row = std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor(std::min(y0, y1) - kMargin)), 0, height - 1);
  const auto last_row = std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor(std::max(y0, y1) + kMargin)), 0, height - 1);
  for (std::int64_t r = first_row; r <= last_row; ++r) {
    // The segment's part within rows [r - margin, r + 1 + margin].
    double ta = 0.0, tb = 1.0;
    const double band_lo = static_cast<double>(r) - kMargin, band_hi = static_cast<double>(r) + 1.0 + kMargin;
    if (std::abs(y1 - y0) > 1e-9) {
      ta = (band_lo - y0) / (y1 - y0);
      tb = (band_hi - y0) / (y1 - y0);
      if (ta > tb) std::swap(ta, tb);
      ta = std::max(ta, 0.0);
      tb = std::min(tb, 1.0);
      if (ta > tb) continue;
    } else if (y0 < band_lo || y0 > band_hi) {
      continue;
    }
    const double xa = x0 + ta * (x1 - x0), xb = x0 + tb * (x1 - x0);
    const auto lo = std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor(std::min(xa, xb) - kMargin)), 0, width - 1);
    const auto hi = std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor(std::max(xa, xb) + kMargin)), 0, width - 1);
    for (std::int64_t i = lo; i <= hi; ++i) out.push_back(static_cast<std::uint32_t>(r * width + i));
  }
}

}  // namespace

EdgeGroundTruth edge_ground_truth(const Soup& soup, const Camera& camera, const EdgeGroundTruthOptions& options) {
  const auto start = Clock::now();
  require_indices_in_range(soup, "edge_ground_truth");
  require_finite_vertices(soup, "edge_ground_truth");
  const double crease_cosine = cosine_of(options.crease_degrees, "the crease angle");
  const double grazing_cosine = cosine_of(options.grazing_degrees, "the grazing angle");
  const CameraFrame frame = camera_frame(camera, "edge_ground_truth");
  const Vec3& eye = camera.eye;

  EdgeGroundTruth out;
  out.width = camera.width;
  out.height = camera.height;
  const std::size_t pixels = std::size_t{camera.width} * camera.height;

  // 1. Classes.
  const CanonicalSoup canonical = canonical_soup(soup);
  const Soup& s = canonical.soup;
  const EdgeTable table = build_edge_table(s);
  const ViewEdges classes = view_edges(s, table, eye, crease_cosine);
  out.stats.profile_edges = classes.count(kProfileEdges);
  out.stats.inner_edges = classes.count(kInnerEdges);
  out.stats.class_seconds = seconds_since(start);

  if (s.triangles.empty()) {  // nothing to see: every pixel none, no hit
    out.profile.assign(pixels, EdgeTruth::none);
    out.inner.assign(pixels, EdgeTruth::none);
    out.grazing.assign(pixels, 0);
    out.hit_triangles.assign(pixels, kNoHit);
    out.stats.seconds = seconds_since(start);
    return out;
  }

  // 2. The centre hits and the grazing flags.
  auto stage = Clock::now();
  ExactImageOptions image_options;
  image_options.footprints = false;
  const ExactImage image = exact_image(soup, {}, camera, image_options);
  out.hit_triangles = image.hit_triangles;
  out.grazing.assign(pixels, 0);
  tbb::parallel_for(tbb::blocked_range<std::uint32_t>(0, camera.height), [&](const auto& rows) {
    for (std::uint32_t r = rows.begin(); r != rows.end(); ++r)
      for (std::uint32_t i = 0; i < camera.width; ++i) {
        const std::size_t p = std::size_t{r} * camera.width + i;
        const std::uint32_t h = image.hit_triangles[p];
        if (h == kNoHit || (image.view_ambiguity[p] & kZeroSign) != 0) continue;
        const Triangle& t = soup.triangles[h];
        const PixelRay ray = pixel_ray(frame, i + 0.5, r + 0.5);
        const Sign above = incidence_angle_sign(soup.vertices[t[0]], soup.vertices[t[1]], soup.vertices[t[2]],
                                                ray.direction, grazing_cosine);
        out.grazing[p] = above == Sign::positive ? 1 : 0;  // exactly at the threshold: not grazing
      }
  });
  out.stats.image_seconds = seconds_since(stage);

  // 3. Visibility, edge by edge.
  stage = Clock::now();
  const Light at_eye{{eye[0], eye[1], eye[2], 1.0}};
  std::vector<Sign> eye_sides(s.triangles.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, s.triangles.size(), 4096), [&](const auto& range) {
    for (std::size_t t = range.begin(); t != range.end(); ++t) {
      const Triangle& tri = s.triangles[t];
      eye_sides[t] = light_orientation(s.vertices[tri[0]], s.vertices[tri[1]], s.vertices[tri[2]], at_eye);
    }
  });
  const detail::BoxTree tree(triangle_boxes(s), detail::LeafTest::exact);
  std::vector<std::uint32_t> edges;
  for (std::size_t e = 0; e < table.size(); ++e)
    if ((classes.classes[e] & (kProfileEdges | kInnerEdges)) != 0) edges.push_back(static_cast<std::uint32_t>(e));

  std::vector<std::uint8_t> marks(pixels, 0);
  std::atomic<std::uint64_t> visible_profile{0}, visible_inner{0}, hidden_intervals{0}, tested{0};
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, edges.size(), 16), [&](const auto& range) {
    std::vector<std::uint32_t> candidates;
    for (std::size_t k = range.begin(); k != range.end(); ++k) {
      const std::uint32_t e = edges[k];
      const std::uint32_t iu = table.edges[e][0], iv = table.edges[e][1];
      const Vec3& u = s.vertices[iu];
      const Vec3& v = s.vertices[iv];
      const bool inner = (classes.classes[e] & kInnerEdges) != 0;
      detail::EdgeVisibility visibility(u, v, eye);
      // Every triangle that can hide a point of the edge meets hull{eye, u, v}, which lies
      // within the edge's box of the segment from its middle to the eye (exact/box_tree.h).
      Vec3 from{}, slack{};
      for (int d = 0; d < 3; ++d) {
        const double lo = std::min(u[d], v[d]), hi = std::max(u[d], v[d]);
        from[d] = std::clamp(lo / 2 + hi / 2, lo, hi);
        slack[d] = std::nextafter(std::max(hi - from[d], from[d] - lo), std::numeric_limits<double>::infinity());
      }
      const auto occlude = [&](std::uint32_t id) {
        const Triangle& t = s.triangles[id];
        const bool has_u = t[0] == iu || t[1] == iu || t[2] == iu, has_v = t[0] == iv || t[1] == iv || t[2] == iv;
        if (has_u && has_v) return true;  // one of the edge's own faces: its plane holds the edge
        visibility.occlude(s.vertices[t[0]], s.vertices[t[1]], s.vertices[t[2]], eye_sides[id]);
        return true;
      };
      if (from == eye) {  // the eye on the edge: the hull is the edge itself
        tree.dilated_segment_query(u, v, Vec3{}, occlude);
      } else {
        tree.dilated_segment_query(from, eye, slack, occlude);
      }
      hidden_intervals += visibility.hidden_intervals();
      const std::vector<detail::ParameterRange> pieces = visibility.visible_pieces();
      if (pieces.empty()) continue;
      (inner ? visible_inner : visible_profile)++;

      candidates.clear();
      for (const detail::ParameterRange& piece : pieces)
        candidate_pixels(frame, visibility.approximate_point(piece.lo), visibility.approximate_point(piece.hi),
                         candidates);
      std::sort(candidates.begin(), candidates.end());
      candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
      const int shift = inner ? 2 : 0;
      for (const std::uint32_t p : candidates) {
        const std::uint32_t r = p / camera.width, i = p % camera.width;
        std::atomic_ref<std::uint8_t> mark(marks[p]);
        if ((mark.load(std::memory_order_relaxed) & (kPasses << shift)) != 0) continue;  // decided already
        const std::array<Vec3, 4> corners{pixel_ray(frame, i, r).direction, pixel_ray(frame, i + 1, r).direction,
                                          pixel_ray(frame, i + 1, r + 1).direction, pixel_ray(frame, i, r + 1).direction};
        ++tested;
        switch (visibility.meets_cone(pieces, corners)) {
          case detail::ConeMeeting::passes:
            mark.fetch_or(static_cast<std::uint8_t>(kPasses << shift), std::memory_order_relaxed);
            break;
          case detail::ConeMeeting::touches:
            mark.fetch_or(static_cast<std::uint8_t>(kTouches << shift), std::memory_order_relaxed);
            break;
          case detail::ConeMeeting::none:
            break;
        }
      }
    }
  });
  out.stats.visible_profile_edges = visible_profile;
  out.stats.visible_inner_edges = visible_inner;
  out.stats.hidden_intervals = hidden_intervals;
  out.stats.pixels_tested = tested;

  // 4. Per pixel and class.
  const auto truth = [](std::uint8_t bits) {
    return (bits & kPasses) != 0 ? EdgeTruth::edge : (bits & kTouches) != 0 ? EdgeTruth::excluded : EdgeTruth::none;
  };
  out.profile.resize(pixels);
  out.inner.resize(pixels);
  for (std::size_t p = 0; p < pixels; ++p) {
    out.profile[p] = truth(marks[p] & 3);
    out.inner[p] = truth(static_cast<std::uint8_t>(marks[p] >> 2));
  }
  out.stats.visibility_seconds = seconds_since(stage);

  if (options.check_footprints) {
    stage = Clock::now();
    const ExactImage footprints = exact_image(soup, {}, camera, {});
    for (std::size_t p = 0; p < pixels; ++p)
      if ((out.profile[p] == EdgeTruth::edge || out.inner[p] == EdgeTruth::edge) && footprints.view_ambiguity[p] == 0)
        ++out.stats.unseen_edge_pixels;
    out.stats.image_seconds += seconds_since(stage);
  }
  out.stats.seconds = seconds_since(start);
  return out;
}

}  // namespace shadowcert
