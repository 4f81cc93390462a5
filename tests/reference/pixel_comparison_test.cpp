// The diff's verdicts without GL (reference/pixel_comparison.h, docs/definitions.md#pixel-protocol): a renderer that
// draws the exact answer agrees everywhere; planted faults are caught. A triangle whose light
// side is flipped (consistently, so its volume stays closed) leaves hard errors exactly where
// its own volume covers an unambiguous pixel; a dropped side quad or a reversed cap leaves the
// captured volume open (io/volume_file.h). Ambiguous pixels never count as errors.
#include "exact/volume_closure.h"
#include "reference/pixel_comparison.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <vector>

#include "support/certificate_test_support.h"
#include "io/volume_file.h"
#include "exact/chain_mesh.h"
#include "exact/edge_multiplicity.h"
#include "exact/shadow_volume_chain.h"
#include "io/soup_file.h"
#include "scene/canonical_soup.h"
#include "scene/edge_table.h"
#include "scene/merged_soup.h"
#include "scene/scene_file.h"

namespace {

using namespace shadowcert;

// data/scenes/default.json merged into one soup (every mesh casts and receives), small image.
struct DefaultScene {
  Soup soup;
  std::vector<Light> lights;
  Camera camera;
};

DefaultScene default_scene(std::uint32_t width = 128, std::uint32_t height = 96) {
  const Scene scene = load_scene(std::filesystem::path(SHADOWCERT_SOURCE_DIR) / "data" / "scenes" / "default.json",
                                 [](const std::filesystem::path& file) { return read_soup(file); });
  DefaultScene d;
  d.soup = merged_soup(scene);
  d.lights = scene.lights;
  d.camera = scene.camera;
  d.camera.width = width;
  d.camera.height = height;
  return d;
}

// What a renderer that draws the exact answer shows, with `counts` as its stencil.
struct Rendering {
  std::uint32_t width = 0, height = 0;
  std::vector<std::uint8_t> covered, lit, counts;

  [[nodiscard]] RenderedPixels pixels(bool with_counts = true) const {
    return {width, height, covered, lit, with_counts ? std::span<const std::uint8_t>(counts)
                                                     : std::span<const std::uint8_t>()};
  }
};

// The stencil a renderer would leave for counts n (mod 256), lit where it counts 0. Where
// the exact count is undefined (only ambiguous pixels) it draws 0.
Rendering rendering_of(const ExactImage& image, const std::vector<std::int64_t>& n) {
  Rendering r{image.width, image.height, {}, {}, {}};
  for (std::size_t p = 0; p < n.size(); ++p) {
    const bool hit = image.hit_triangles[p] != kNoHit;
    const auto count = static_cast<std::uint8_t>(((n[p] % 256) + 256) % 256);
    r.covered.push_back(hit ? 255 : 0);
    r.counts.push_back(hit ? count : 0);
    r.lit.push_back(count == 0 ? 255 : 0);
  }
  return r;
}

std::vector<std::int64_t> exact_counts(const ExactImage& image) {
  std::vector<std::int64_t> n;
  for (std::uint32_t c : image.lights.at(0).counts) n.push_back(c == kNoHit || c == kUndefinedCount ? 0 : c);
  return n;
}

std::uint64_t unambiguous(const ExactImage& image) {
  std::uint64_t n = 0;
  for (std::uint8_t a : image.lights.at(0).ambiguity) n += a == 0;
  return n;
}

TEST(PixelComparison, ExactRendering_AgreesOnEveryUnambiguousPixel) {
  const DefaultScene s = default_scene();
  const ExactImage image = exact_image(s.soup, s.lights, s.camera);
  const Rendering r = rendering_of(image, exact_counts(image));
  for (bool with_counts : {true, false}) {
    const PixelComparison c = compare_pixels(image, 0, r.pixels(with_counts));
    EXPECT_EQ(c.hard_errors, 0u);
    EXPECT_EQ(c.agree, unambiguous(image));
    EXPECT_EQ(c.agree + c.ambiguous, std::uint64_t{image.width} * image.height);
  }
  EXPECT_GT(unambiguous(image), image.width * image.height / 2);  // the verdicts are not vacuous
}

TEST(PixelComparison, FlippedTriangleSign_IsCaughtAsHardErrorsInItsVolume) {
  const DefaultScene s = default_scene(256, 192);
  const ExactImage image = exact_image(s.soup, s.lights, s.camera);
  // The flipped triangle t: one of the open box's (floor: 2 triangles, fan: 16 blades, then
  // the box), whose own shadow covers unambiguous floor pixels.
  const std::uint32_t t = 2 + 16 + 4;
  // [P in V(t)] exactly: the same image with t made a point (it then neither casts nor is hit)
  // counts one less wherever the centre ray hits the same triangle as before.
  Soup without = s.soup;
  without.triangles[t] = {without.triangles[t][0], without.triangles[t][0], without.triangles[t][0]};
  const ExactImage other = exact_image(without, s.lights, s.camera);
  // A consistent flip turns t's volume inside out: the stencil counts n - 2 [P in V(t)].
  std::vector<std::int64_t> n = exact_counts(image);
  std::uint64_t expected = 0;
  for (std::size_t p = 0; p < n.size(); ++p) {
    const std::uint32_t a = image.lights[0].counts[p], b = other.lights[0].counts[p];
    if (image.hit_triangles[p] != other.hit_triangles[p] || image.hit_triangles[p] == t) continue;
    if (a == kNoHit || a == kUndefinedCount || b == kUndefinedCount || a == b) continue;
    ASSERT_EQ(a, b + 1) << "pixel " << p;
    n[p] -= 2;
    expected += image.lights[0].ambiguity[p] == 0;
  }
  ASSERT_GT(expected, 30u);  // t does shadow part of the floor in view
  const PixelComparison c = compare_pixels(image, 0, rendering_of(image, n).pixels());
  EXPECT_EQ(c.hard_errors, expected);
  EXPECT_EQ(c.coverage_errors, 0u);
  EXPECT_EQ(c.lit_errors + c.count_errors, expected);
  // A mask-only comparison sees only the pixels whose lit state changed (n = 2 drawn as 0).
  EXPECT_LE(compare_pixels(image, 0, rendering_of(image, n).pixels(false)).hard_errors, expected);
}

TEST(PixelComparison, AmbiguousPixels_AreNeverHardErrors) {
  const DefaultScene s = default_scene();
  const ExactImage image = exact_image(s.soup, s.lights, s.camera);
  Rendering r = rendering_of(image, exact_counts(image));
  std::uint64_t ambiguous = 0;
  for (std::size_t p = 0; p < r.covered.size(); ++p) {
    if (image.lights[0].ambiguity[p] == 0) continue;
    ++ambiguous;
    r.covered[p] = 255;  // whatever a renderer draws there
    r.lit[p] = r.lit[p] != 0 ? 0 : 255;
    r.counts[p] = static_cast<std::uint8_t>(r.counts[p] + 7);
  }
  ASSERT_GT(ambiguous, 0u);
  const PixelComparison c = compare_pixels(image, 0, r.pixels());
  EXPECT_EQ(c.hard_errors, 0u);
  EXPECT_EQ(c.ambiguous, ambiguous);
}

TEST(PixelComparison, EachKindOfMismatch_IsOneHardError) {
  const DefaultScene s = default_scene();
  const ExactImage image = exact_image(s.soup, s.lights, s.camera);
  const ExactLightImage& e = image.lights[0];
  constexpr std::size_t kNone = SIZE_MAX;
  std::size_t background = kNone, lit = kNone, shadowed = kNone;  // unambiguous pixels of each kind
  for (std::size_t p = 0; p < e.counts.size(); ++p) {
    if (e.ambiguity[p] != 0) continue;
    if (e.counts[p] == kNoHit) background = p;
    else if (e.counts[p] == 0) lit = p;
    else shadowed = p;
  }
  ASSERT_TRUE(background != kNone && lit != kNone && shadowed != kNone);
  Rendering r = rendering_of(image, exact_counts(image));
  r.covered[background] = 255;                                    // drawn where nothing is
  r.lit[lit] = 0;                                                 // shadowed where lit
  r.counts[lit] = 1;
  r.counts[shadowed] = static_cast<std::uint8_t>(r.counts[shadowed] + 1);  // wrong count, still shadowed
  r.lit[shadowed] = 0;
  const PixelComparison c = compare_pixels(image, 0, r.pixels());
  EXPECT_EQ(c.hard_errors, 3u);
  EXPECT_EQ(c.coverage_errors, 1u);
  EXPECT_EQ(c.lit_errors, 1u);
  EXPECT_EQ(c.count_errors, 1u);
  EXPECT_EQ(c.verdicts[background], PixelVerdict::hard_error);
  // A mask-only method is not asked for counts.
  EXPECT_EQ(compare_pixels(image, 0, r.pixels(false)).hard_errors, 2u);
}

// Stencil counts wrap (docs/definitions.md#pixel-protocol): 256 crossings leave 0 in an 8-bit stencil, which agrees
// with n = 256 for a counting method; a mask-only method has no such excuse.
TEST(PixelComparison, CountsAreComparedModulo256) {
  ExactImage image;
  image.width = 3;
  image.height = 1;
  image.hit_triangles = {0, 0, 0};
  image.lights.push_back({{256, 3, 257}, {0, 0, 0}, {0, 0, 0}});
  const std::vector<std::uint8_t> covered{255, 255, 255}, lit{255, 0, 0}, counts{0, 3, 2};
  const PixelComparison c = compare_pixels(image, 0, {3, 1, covered, lit, counts});
  EXPECT_EQ(c.agree, 2u);
  EXPECT_EQ(c.count_errors, 1u);  // 257 is 1 modulo 256, not 2
  EXPECT_EQ(c.verdicts[0], PixelVerdict::agree);
  const PixelComparison mask_only = compare_pixels(image, 0, {3, 1, covered, lit, {}});
  EXPECT_EQ(mask_only.lit_errors, 1u);  // pixel 0: shadowed (n = 256) drawn lit
  EXPECT_EQ(mask_only.verdicts[0], PixelVerdict::hard_error);
}

TEST(PixelComparison, MismatchedSizes_Throw) {
  const DefaultScene s = default_scene();
  const ExactImage image = exact_image(s.soup, s.lights, s.camera);
  Rendering r = rendering_of(image, exact_counts(image));
  r.width += 1;
  EXPECT_THROW((void)compare_pixels(image, 0, r.pixels()), std::invalid_argument);
  EXPECT_THROW((void)compare_pixels(image, 1, rendering_of(image, exact_counts(image)).pixels()),
               std::invalid_argument);
}

// --- closure of a captured volume, with planted faults -----------------------------------------

HomogeneousMesh default_scene_volume() {
  const DefaultScene s = default_scene();
  const Soup canonical = canonical_soup(s.soup).soup;
  const EdgeTable table = build_edge_table(canonical);
  const Light& light = s.lights.at(0);
  return chain_mesh(assemble_chain(canonical, table, exact_multiplicities(canonical, table, light), light), canonical,
                    light);
}

TEST(VolumeClosure, ExactChainMesh_IsClosed) {
  EXPECT_TRUE(certify_volume_closure(default_scene_volume()).certificate.closed);
}

TEST(VolumeClosure, DroppedSideQuad_IsAnOpenVolume) {
  HomogeneousMesh mesh = default_scene_volume();
  // chain_mesh writes the quads last, each as two triangles: drop the last quad.
  ASSERT_GE(mesh.triangles.size(), 2u);
  mesh.triangles.resize(mesh.triangles.size() - 2);
  const VolumeClosure c = certify_volume_closure(mesh);
  EXPECT_FALSE(c.certificate.closed);
  // Its four edges, less the diagonal both halves shared.
  EXPECT_EQ(c.certificate.unbalanced.size(), 4u);
}

TEST(VolumeClosure, ReversedCap_IsAnOpenVolume) {
  HomogeneousMesh mesh = default_scene_volume();
  std::swap(mesh.triangles.front()[1], mesh.triangles.front()[2]);  // a front cap, sign flipped
  const VolumeClosure c = certify_volume_closure(mesh);
  EXPECT_FALSE(c.certificate.closed);
  EXPECT_EQ(c.certificate.unbalanced.size(), 3u);
  for (const UnbalancedEdge& e : c.certificate.unbalanced) EXPECT_EQ(std::abs(e.excess), 2);
}

}  // namespace
