#include "gpu/flat_soup_renderer.h"

#include <gtest/gtest.h>

#include <array>

#include "support/gl_test_support.h"
#include "gpu/camera_transform.h"
#include "gpu/gl_error.h"
#include "gpu/offscreen_target.h"
#include "gpu/png_image.h"
#include "square_test_camera.h"

namespace shadowcert::gpu {
namespace {

using test::GlTest;

// Apex up: image vertices (16, 48), (48, 48), (32, 16). Not symmetric top/bottom, so a
// readback that forgot to flip rows fails the checks below.
Soup apex_up_triangle(int copies) {
  Soup soup;
  soup.vertices = {{-2.5, -2.5, 0.0}, {2.5, -2.5, 0.0}, {0.0, 2.5, 0.0}};
  for (int i = 0; i < copies; ++i) {
    // Alternate orientations: counting must not depend on facing.
    soup.triangles.push_back(i % 2 == 0 ? Triangle{0, 1, 2} : Triangle{0, 2, 1});
  }
  return soup;
}

// Pixels whose centres are at least 1.5 px from every edge of the triangle.
constexpr std::array<std::array<std::uint32_t, 2>, 4> kInside{{{32, 20}, {32, 37}, {20, 44}, {44, 44}}};
constexpr std::array<std::array<std::uint32_t, 2>, 5> kOutside{{{2, 2}, {20, 20}, {44, 20}, {32, 12}, {32, 52}}};

// The GL context fixture (support/gl_test_support.h) under this unit's name, for
// --gtest_filter=FlatSoupRendererTest.*
class FlatSoupRendererTest : public GlTest {};

TEST_F(FlatSoupRendererTest, TriangleColoursKnownPixelsTopRowFirst) {
  const Camera camera = square_test_camera();
  OffscreenTarget target(camera.width, camera.height);
  target.bind();
  target.clear({0.0f, 0.0f, 0.0f, 1.0f});
  const SoupMesh mesh(apex_up_triangle(1));
  FlatSoupRenderer renderer;
  // 0.2 * 255 = 51 exactly after rounding: a colour RGBA8 stores without doubt.
  renderer.draw(mesh, camera, {.colour = {1.0f, 0.2f, 0.0f, 1.0f}});
  const RgbaImage image = target.read_colour();
  ASSERT_EQ(image.width, 64u);
  ASSERT_EQ(image.height, 64u);
  for (const auto& [x, row] : kInside) {
    const std::uint8_t* p = image.at(x, row);
    EXPECT_EQ((std::array<int, 4>{p[0], p[1], p[2], p[3]}), (std::array<int, 4>{255, 51, 0, 255}))
        << "inside pixel " << x << "," << row;
  }
  for (const auto& [x, row] : kOutside) {
    const std::uint8_t* p = image.at(x, row);
    EXPECT_EQ((std::array<int, 4>{p[0], p[1], p[2], p[3]}), (std::array<int, 4>{0, 0, 0, 255}))
        << "outside pixel " << x << "," << row;
  }
}

TEST_F(FlatSoupRendererTest, StencilCountsEveryTriangleCoveringAPixel) {
  const Camera camera = square_test_camera();
  OffscreenTarget target(camera.width, camera.height);
  target.bind();
  target.clear();
  const SoupMesh mesh(apex_up_triangle(3));
  FlatSoupRenderer renderer;
  renderer.draw(mesh, camera, {.depth_test = false, .count_in_stencil = true});
  const GrayImage stencil = target.read_stencil();
  for (const auto& [x, row] : kInside) EXPECT_EQ(*stencil.at(x, row), 3) << x << "," << row;
  for (const auto& [x, row] : kOutside) EXPECT_EQ(*stencil.at(x, row), 0) << x << "," << row;
  // Rasterisation covers each pixel centre by all three copies or by none.
  for (std::uint8_t count : stencil.pixels) EXPECT_TRUE(count == 0 || count == 3);

  const GrayImage lit = lit_mask(stencil);
  for (const auto& [x, row] : kInside) EXPECT_EQ(*lit.at(x, row), 0);
  for (const auto& [x, row] : kOutside) EXPECT_EQ(*lit.at(x, row), 255);
}

TEST_F(FlatSoupRendererTest, StencilCountsWrapModulo256) {
  const Camera camera = square_test_camera();
  OffscreenTarget target(camera.width, camera.height);
  target.bind();
  target.clear();
  FlatSoupRenderer renderer;
  renderer.draw(SoupMesh(apex_up_triangle(257)), camera, {.depth_test = false, .count_in_stencil = true});
  const GrayImage stencil = target.read_stencil();
  for (const auto& [x, row] : kInside) EXPECT_EQ(*stencil.at(x, row), 1);  // 257 mod 256
}

TEST_F(FlatSoupRendererTest, DepthTestKeepsTheNearerTriangle) {
  const Camera camera = square_test_camera();
  OffscreenTarget target(camera.width, camera.height);
  target.bind();
  target.clear();
  FlatSoupRenderer renderer;
  Soup near = apex_up_triangle(1);
  Soup far = apex_up_triangle(1);
  for (Vec3& v : far.vertices) v = {v[0] * 2.0, v[1] * 2.0, -5.0};  // same image footprint, behind
  renderer.draw(SoupMesh(near), camera, {.colour = {0.0f, 1.0f, 0.0f, 1.0f}});
  renderer.draw(SoupMesh(far), camera, {.colour = {1.0f, 0.0f, 0.0f, 1.0f}});
  const RgbaImage image = target.read_colour();
  for (const auto& [x, row] : kInside) EXPECT_EQ(image.at(x, row)[1], 255) << x << "," << row;
}

TEST_F(FlatSoupRendererTest, RenderedImagesWriteAsPng) {
  const Camera camera = square_test_camera();
  OffscreenTarget target(camera.width, camera.height);
  target.bind();
  target.clear();
  FlatSoupRenderer renderer;
  renderer.draw(SoupMesh(apex_up_triangle(2)), camera, {.count_in_stencil = true});
  const std::string dir = ::testing::TempDir();
  EXPECT_NO_THROW(write_png(dir + "shadowcert_triangle.png", target.read_colour()));
  EXPECT_NO_THROW(write_png(dir + "shadowcert_triangle_stencil.png", target.read_stencil()));
}

TEST_F(FlatSoupRendererTest, OffscreenTargetRejectsEmptySize) { EXPECT_THROW(OffscreenTarget(0, 4), GlError); }

}  // namespace
}  // namespace shadowcert::gpu
