// The scores of reference/edge_scores.h: a perfect detector (the ground truth itself) scores
// exactly 1 at every tolerance, a detector shifted by one pixel scores 1 within one pixel and
// less at zero, the benchmark's one-to-one matching on hand-made lines, thinning, excluded and
// grazing pixels, the best threshold over several images, input validation.
#include "reference/edge_scores.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <stdexcept>
#include <vector>

#include "reference/edge_ground_truth.h"
#include "scene/procedural_mesh.h"
#include "support/certificate_test_support.h"

namespace {

using namespace shadowcert;

struct Image {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::vector<EdgeTruth> truth;
  std::vector<std::uint8_t> grazing;
  std::vector<float> intensity;

  Image(std::uint32_t w, std::uint32_t h)
      : width(w), height(h), truth(std::size_t{w} * h, EdgeTruth::none), grazing(std::size_t{w} * h, 0),
        intensity(std::size_t{w} * h, 0.0f) {}
  std::size_t at(std::uint32_t x, std::uint32_t y) const { return std::size_t{y} * width + x; }
  EdgeScoreInput input() const { return {width, height, truth, grazing, intensity}; }
};

EdgeMatchCounts score(const Image& image, const EdgeTolerance& tolerance, double threshold = 0.5) {
  const std::vector<double> t{threshold};
  return score_edges(image.input(), tolerance, t).front();
}

const EdgeTolerance kExact{EdgeMatching::window, 0, 0.0075};
const EdgeTolerance kOnePixel{EdgeMatching::window, 1, 0.0075};
const EdgeTolerance kTwoPixels{EdgeMatching::window, 2, 0.0075};
const EdgeTolerance kBsds{EdgeMatching::bsds, 0, 0.0075};

TEST(EdgeScores, PerfectDetectorScoresOneEverywhere) {
  // The ground truth of a real scene as the detector's intensities: 1 on truth pixels.
  Soup soup = floor_quad(3.0);
  test_support::append(soup, box({-0.5, 0.0, -0.5}, {0.5, 1.0, 0.5}));
  test_support::append(soup, uv_sphere({1.5, 0.6, 0.5}, 0.6, 12, 8));
  soup.normals.clear();
  Camera camera;
  camera.eye = {3.0, 2.5, 4.0};
  camera.target = {0.0, 0.5, 0.0};
  camera.width = 160;
  camera.height = 120;
  const EdgeGroundTruth truth = edge_ground_truth(soup, camera);
  const std::vector<double> thresholds = default_edge_thresholds();
  for (const bool inner : {false, true}) {
    std::vector<float> intensity(truth.profile.size());
    const std::span<const EdgeTruth> t = truth.truth(inner);
    for (std::size_t p = 0; p < intensity.size(); ++p) intensity[p] = t[p] == EdgeTruth::edge ? 1.0f : 0.0f;
    const EdgeScoreInput input{truth.width, truth.height, t, truth.grazing, intensity};
    for (const EdgeTolerance& tolerance : {kExact, kOnePixel, kTwoPixels, kBsds}) {
      SCOPED_TRACE(tolerance.name() + (inner ? " inner" : " profile"));
      for (const EdgeMatchCounts& c : score_edges(input, tolerance, thresholds)) {
        EXPECT_GT(c.truth, 20u);
        EXPECT_EQ(c.precision(), 1.0);
        EXPECT_EQ(c.recall(), 1.0);
        EXPECT_EQ(c.f1(), 1.0);
        EXPECT_EQ(c.grazing_false, 0u);
      }
    }
    // Nothing is detected at threshold 1: vacuous precision, no recall.
    const std::vector<double> one{1.0};
    const EdgeMatchCounts none = score_edges(input, kOnePixel, one).front();
    EXPECT_EQ(none.detections, 0u);
    EXPECT_EQ(none.precision(), 1.0);
    EXPECT_EQ(none.recall(), 0.0);
    EXPECT_EQ(none.f1(), 0.0);
  }
}

TEST(EdgeScores, ShiftedByOnePixel) {
  // A closed rectangle outline of truth; the detector sees it one pixel to the right.
  Image image(40, 30);
  for (std::uint32_t x = 10; x <= 30; ++x) image.truth[image.at(x, 8)] = image.truth[image.at(x, 20)] = EdgeTruth::edge;
  for (std::uint32_t y = 8; y <= 20; ++y) image.truth[image.at(10, y)] = image.truth[image.at(30, y)] = EdgeTruth::edge;
  for (std::uint32_t y = 0; y < 30; ++y)
    for (std::uint32_t x = 0; x + 1 < 40; ++x)
      if (image.truth[image.at(x, y)] == EdgeTruth::edge) image.intensity[image.at(x + 1, y)] = 0.8f;
  const EdgeMatchCounts one = score(image, kOnePixel);
  EXPECT_EQ(one.precision(), 1.0);
  EXPECT_EQ(one.recall(), 1.0);
  EXPECT_EQ(score(image, kTwoPixels).f1(), 1.0);
  // At zero pixels only the horizontal runs overlap (but an end each): 40 of 64 both ways.
  const EdgeMatchCounts exact = score(image, kExact);
  EXPECT_EQ(exact.detections, 64u);
  EXPECT_EQ(exact.true_detections, 40u);
  EXPECT_EQ(exact.truth, 64u);
  EXPECT_EQ(exact.found, 40u);
  // The verdicts per pixel say the same.
  const std::vector<EdgeVerdict> verdicts = edge_verdicts(image.input(), 0, 0.5);
  const auto verdict_count = [&](EdgeVerdict v) { return std::count(verdicts.begin(), verdicts.end(), v); };
  EXPECT_EQ(verdict_count(EdgeVerdict::true_detection), 40);
  EXPECT_EQ(verdict_count(EdgeVerdict::false_detection), 24);
  EXPECT_EQ(verdict_count(EdgeVerdict::missed), 24);
  EXPECT_EQ(verdict_count(EdgeVerdict::found), 0);
  const std::vector<EdgeVerdict> within_one = edge_verdicts(image.input(), 1, 0.5);
  EXPECT_EQ(std::count(within_one.begin(), within_one.end(), EdgeVerdict::false_detection), 0);
  EXPECT_EQ(std::count(within_one.begin(), within_one.end(), EdgeVerdict::missed), 0);
  EXPECT_EQ(std::count(within_one.begin(), within_one.end(), EdgeVerdict::found), 24);
  // A one-pixel shift is far inside the benchmark's reach (0.0075 of a 50-pixel diagonal is
  // 0.375 pixels: nothing), so at this size it fails the vertical sides.
  EXPECT_LT(score(image, kBsds).recall(), 1.0);
}

TEST(EdgeScores, BenchmarkMatchesOneToOne) {
  // 200 x 150: the benchmark's reach is 0.0075 * 250 = 1.875 pixels. One truth line, the
  // detector draws two parallel lines a pixel above and below it: the window counts every
  // detection true, the benchmark pairs each truth pixel with one detection only.
  Image image(200, 150);
  for (std::uint32_t x = 50; x < 150; ++x) {
    image.truth[image.at(x, 75)] = EdgeTruth::edge;
    image.intensity[image.at(x, 74)] = image.intensity[image.at(x, 76)] = 0.9f;
  }
  const EdgeMatchCounts window = score(image, kOnePixel);
  EXPECT_EQ(window.detections, 200u);
  EXPECT_EQ(window.true_detections, 200u);
  EXPECT_EQ(window.found, 100u);
  EXPECT_EQ(score(image, kExact).true_detections, 0u);
  const EdgeMatchCounts bsds = score(image, kBsds);
  EXPECT_EQ(bsds.truth, 100u);
  EXPECT_EQ(bsds.detections, 200u);
  EXPECT_EQ(bsds.true_detections, 100u);  // one detection per truth pixel
  EXPECT_EQ(bsds.found, 100u);
  EXPECT_DOUBLE_EQ(bsds.precision(), 0.5);
  EXPECT_DOUBLE_EQ(bsds.recall(), 1.0);
  // Lines three pixels away are out of the benchmark's reach.
  Image far(200, 150);
  for (std::uint32_t x = 50; x < 150; ++x) {
    far.truth[far.at(x, 75)] = EdgeTruth::edge;
    far.intensity[far.at(x, 72)] = 0.9f;
  }
  EXPECT_EQ(score(far, kBsds).true_detections, 0u);

  // A two-pixel-wide detection over a one-pixel truth: thinned first, then matched: perfect.
  Image wide(200, 150);
  for (std::uint32_t x = 50; x < 150; ++x) {
    wide.truth[wide.at(x, 75)] = EdgeTruth::edge;
    wide.intensity[wide.at(x, 75)] = wide.intensity[wide.at(x, 76)] = 0.9f;
  }
  const EdgeMatchCounts thinned = score(wide, kBsds);
  EXPECT_LE(thinned.detections, 100u);
  EXPECT_EQ(thinned.precision(), 1.0);
  EXPECT_GE(thinned.recall(), 0.98);  // the thinned line may lose an end pixel
  EXPECT_EQ(score(wide, kOnePixel).detections, 200u);  // the window does not thin
}

TEST(EdgeScores, ThinningKeepsLinesOnePixelWide) {
  const std::uint32_t w = 30, h = 12;
  std::vector<std::uint8_t> bar(std::size_t{w} * h, 0);
  for (std::uint32_t y = 4; y < 7; ++y)
    for (std::uint32_t x = 3; x < 27; ++x) bar[std::size_t{y} * w + x] = 1;
  const std::vector<std::uint8_t> thin = thin_edges(bar, w, h);
  for (std::uint32_t x = 6; x < 24; ++x) {
    int column = 0;
    for (std::uint32_t y = 0; y < h; ++y) column += thin[std::size_t{y} * w + x];
    EXPECT_EQ(column, 1) << x;
  }
  // A one-pixel line stays as it is; a 2 x 2 block keeps a pixel.
  std::vector<std::uint8_t> line(std::size_t{w} * h, 0);
  for (std::uint32_t x = 3; x < 27; ++x) line[std::size_t{5} * w + x] = 1;
  EXPECT_EQ(thin_edges(line, w, h), line);
  std::vector<std::uint8_t> block(std::size_t{w} * h, 0);
  block[std::size_t{5} * w + 5] = block[std::size_t{5} * w + 6] = block[std::size_t{6} * w + 5] = block[std::size_t{6} * w + 6] = 1;
  const std::vector<std::uint8_t> b = thin_edges(block, w, h);
  EXPECT_GE(std::count(b.begin(), b.end(), 1), 1);
  EXPECT_THROW((void)thin_edges(block, w, h + 1), std::invalid_argument);
}

// The thinning's conditions applied by scanning the whole image every sub-iteration (what
// thin_edges does on a work list), for random blobs.
std::vector<std::uint8_t> thin_by_scanning(std::vector<std::uint8_t> m, int w, int h) {
  const auto at = [&](int x, int y) -> int { return x < 0 || y < 0 || x >= w || y >= h ? 0 : m[std::size_t(y * w + x)]; };
  for (bool changed = true; changed;) {
    changed = false;
    for (int pass = 0; pass < 2; ++pass) {
      std::vector<std::size_t> remove;
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          if (!at(x, y)) continue;
          const int n[9] = {at(x + 1, y), at(x + 1, y - 1), at(x, y - 1), at(x - 1, y - 1), at(x - 1, y),
                            at(x - 1, y + 1), at(x, y + 1), at(x + 1, y + 1), at(x + 1, y)};
          int crossings = 0, n1 = 0, n2 = 0;
          for (int i = 0; i < 4; ++i) {
            crossings += n[2 * i] == 0 && (n[2 * i + 1] || n[2 * i + 2]);
            n1 += (n[2 * i] | n[2 * i + 1]) != 0;
            n2 += (n[2 * i + 1] | n[2 * i + 2]) != 0;
          }
          const int least = std::min(n1, n2);
          const bool g3 = pass == 0 ? ((n[1] | n[2] | (1 - n[7])) & n[0]) == 0 : ((n[5] | n[6] | (1 - n[3])) & n[4]) == 0;
          if (crossings == 1 && least >= 2 && least <= 3 && g3) remove.push_back(std::size_t(y * w + x));
        }
      for (std::size_t q : remove) m[q] = 0;
      changed |= !remove.empty();
    }
  }
  return m;
}

TEST(EdgeScores, ThinningMatchesAFullScan) {
  std::mt19937 random(7);
  const int w = 61, h = 47;
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<std::uint8_t> m(std::size_t(w) * h, 0);
    std::uniform_int_distribution<int> px(0, w - 1), py(0, h - 1), radius(1, 6);
    for (int k = 0; k < 12; ++k) {  // discs and random specks
      const int cx = px(random), cy = py(random), r = radius(random);
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
          if ((x - cx) * (x - cx) + (y - cy) * (y - cy) <= r * r) m[std::size_t(y * w + x)] = 1;
    }
    for (int k = 0; k < 200; ++k) m[std::size_t(py(random) * w + px(random))] = 1;
    EXPECT_EQ(thin_edges(m, w, h), thin_by_scanning(m, w, h)) << trial;
  }
}

TEST(EdgeScores, ExcludedAndGrazingPixels) {
  Image image(20, 20);
  for (std::uint32_t x = 2; x < 18; ++x) image.truth[image.at(x, 10)] = EdgeTruth::edge;
  image.truth[image.at(5, 3)] = EdgeTruth::excluded;
  image.intensity[image.at(5, 3)] = 1.0f;  // a detection on an excluded pixel: counts nowhere
  for (std::uint32_t x = 0; x < 20; ++x) image.grazing[image.at(x, 16)] = 1;
  image.intensity[image.at(7, 16)] = image.intensity[image.at(8, 16)] = 1.0f;  // false edges, grazing
  image.intensity[image.at(7, 1)] = 1.0f;                                      // a false edge elsewhere
  for (std::uint32_t x = 2; x < 18; ++x) image.intensity[image.at(x, 10)] = 1.0f;
  const EdgeMatchCounts c = score(image, kOnePixel);
  EXPECT_EQ(c.truth, 16u);
  EXPECT_EQ(c.found, 16u);
  EXPECT_EQ(c.detections, 19u);
  EXPECT_EQ(c.true_detections, 16u);
  EXPECT_EQ(c.grazing_false, 2u);
  EXPECT_EQ(c.grazing_pixels, 20u);
  EXPECT_DOUBLE_EQ(c.grazing_false_rate(), 0.1);
  const EdgeMatchCounts b = score(image, kBsds);
  EXPECT_EQ(b.grazing_false, 2u);
}

TEST(EdgeScores, BestThresholdOverSeveralImages) {
  const auto counts = [](std::uint64_t d, std::uint64_t td, std::uint64_t t, std::uint64_t f) {
    EdgeMatchCounts c;
    c.detections = d;
    c.true_detections = td;
    c.truth = t;
    c.found = f;
    return c;
  };
  // Summed: threshold 0 gives P = 0.5, R = 1 (F 0.667); threshold 1 gives P = 1, R = 0.75
  // (F 0.857); threshold 2 gives P = 1, R = 0.25.
  const std::vector<std::vector<EdgeMatchCounts>> curves{
      {counts(20, 10, 10, 10), counts(8, 8, 10, 8), counts(2, 2, 10, 2)},
      {counts(20, 10, 10, 10), counts(7, 7, 10, 7), counts(3, 3, 10, 3)}};
  EXPECT_EQ(best_threshold(curves), 1u);
  EXPECT_THROW((void)best_threshold(std::span<const std::vector<EdgeMatchCounts>>{}), std::invalid_argument);
}

TEST(EdgeScores, RejectsBadInput) {
  Image image(8, 6);
  EdgeScoreInput input = image.input();
  input.height = 7;
  const std::vector<double> t{0.5};
  EXPECT_THROW((void)score_edges(input, kOnePixel, t), std::invalid_argument);
  EdgeTolerance bad = kBsds;
  bad.bsds_fraction = 0.0;
  EXPECT_THROW((void)score_edges(image.input(), bad, t), std::invalid_argument);
  EXPECT_EQ(kBsds.name(), "bsds");
  EXPECT_EQ(kTwoPixels.name(), "2px");
}

}  // namespace
