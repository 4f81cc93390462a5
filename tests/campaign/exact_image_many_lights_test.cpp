// The exact image with many point lights and no footprints (reference/exact_image.h: the soft
// reference's mode, where every light is counted in one pass per hit point) against the same
// image light by light: every count, lit bit and ambiguity bit equal. The scenes are the hard
// ones (data/scenes/, its hard/ folder, campaign/hard_scene.h's), the bundled meshes over a
// floor and the campaign's random soups; the lights are each scene's own point lights, a jittered
// disk of samples around the first, lights exactly at soup vertices and on an edge's line (zero
// signs: segments that touch), and lights at a pixel's hit point rounded to doubles (the lights
// within rounding of P, which are counted alone). Without light images (the soft reference's
// ExactLightTally) the per-pixel sums are those of the light images.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "campaign/campaign_view.h"
#include "campaign/hard_scene.h"
#include "campaign/random_soup.h"
#include "core/pixel_ray.h"
#include "io/soup_file.h"
#include "reference/disk_light.h"
#include "reference/exact_image.h"
#include "scene/framed_scene.h"
#include "scene/merged_soup.h"
#include "scene/scene_file.h"
#include "support/mesh_data.h"

namespace {

using namespace shadowcert;

struct Case {
  std::string name;
  Soup soup;
  std::vector<Light> lights;  // the scene's own
  Camera camera;
  std::vector<std::uint8_t> casts;
};

constexpr std::uint32_t kWidth = 32, kHeight = 24;

Camera sized(Camera camera) {
  camera.width = kWidth;
  camera.height = kHeight;
  return camera;
}

void add_scene_files(std::vector<Case>& cases, const std::filesystem::path& folder) {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(folder))
    if (entry.path().extension() == ".json" && entry.path().stem() != "sphere_grid_1m") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  for (const auto& file : files) {
    const Scene scene = load_scene(file, [](const std::filesystem::path& p) { return read_soup(p); });
    Case c{folder.filename().string() + "/" + file.filename().string(), merged_soup(scene), scene.lights,
           sized(scene.camera), {}};
    if (!std::all_of(scene.meshes.begin(), scene.meshes.end(), [](const SceneMesh& m) { return m.casts; }))
      c.casts = casting_triangles(scene);
    cases.push_back(std::move(c));
  }
}

// `mesh` framed over a floor (scene/framed_scene.h), the floor receiving only.
Case mesh_case(const std::string& name, const Soup& mesh) {
  const Scene scene = framed_mesh_scene(mesh, name, {kWidth, kHeight});
  return {name, merged_soup(scene), scene.lights, sized(scene.camera), casting_triangles(scene)};
}

std::vector<Case> cases() {
  std::vector<Case> out;
  const std::filesystem::path scenes = std::filesystem::path(SHADOWCERT_SOURCE_DIR) / "data" / "scenes";
  add_scene_files(out, scenes);
  add_scene_files(out, scenes / "hard");
  for (std::string_view relative : test::kBundledMeshes)
    out.push_back(mesh_case(std::string(relative), read_soup(test::mesh_file(relative))));
  for (std::uint64_t index = 0; index < 8; ++index) {
    const HardSceneCase hard = hard_scene_case(3, index, kWidth, kHeight);
    out.push_back({"hard_scene/3/" + std::to_string(index), merged_soup(hard.scene), hard.scene.lights,
                   sized(hard.scene.camera), {}});
  }
  for (std::uint64_t index = 0; index < 12; ++index) {
    const CampaignCase cc = campaign_case(11, index, 24);
    const CampaignView view = campaign_view(cc, kWidth, kHeight);
    Case c{"campaign/11/" + std::to_string(index), view.floor, {view.light}, view.camera, {}};
    append_soup(c.soup, view.soup);
    out.push_back(std::move(c));
  }
  return out;
}

// The lights the case is imaged under: see the file comment. Only point lights: a directional
// light is never counted with others.
std::vector<Light> lights_of(const Case& c) {
  std::vector<Light> lights;
  for (const Light& l : c.lights)
    if (!l.directional()) lights.push_back(l);
  Vec3 lo = c.soup.vertices.front(), hi = lo;
  for (const Vec3& v : c.soup.vertices)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], v[k]);
      hi[k] = std::max(hi[k], v[k]);
    }
  const double size = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  const Light first = lights.empty() ? Light{{(lo[0] + hi[0]) / 2, hi[1] + size, (lo[2] + hi[2]) / 2, 1.0}} : lights[0];
  const std::vector<Light> disk = disk_light_samples(first, scene_bounds_centre(c.soup), {0.05 * size, 9, 5});
  lights.insert(lights.end(), disk.begin(), disk.end());
  // Soup vertices and an edge's midpoint (exactly on its line where the halving is exact).
  const std::size_t step = std::max<std::size_t>(1, c.soup.triangles.size() / 3);
  for (std::size_t t = 0; t < c.soup.triangles.size(); t += step) {
    const Vec3& a = c.soup.vertices[c.soup.triangles[t][0]];
    const Vec3& b = c.soup.vertices[c.soup.triangles[t][1]];
    lights.push_back(Light{{a[0], a[1], a[2], 1.0}});
    lights.push_back(Light{{a[0] / 2 + b[0] / 2, a[1] / 2 + b[1] / 2, a[2] / 2 + b[2] / 2, 1.0}});
  }
  // The centre ray of a few pixels, at the first hit a float ray caster finds (within rounding
  // of the exact P): a light there lies in P's enclosure.
  const CameraFrame frame = camera_frame(c.camera, "lights_of");
  for (const auto& [i, r] : {std::pair{kWidth / 2, kHeight / 2}, std::pair{kWidth / 3, 2 * kHeight / 3}}) {
    const PixelRay ray = pixel_ray(frame, i + 0.5, r + 0.5);
    double best = std::numeric_limits<double>::infinity();
    for (const Triangle& t : c.soup.triangles) {
      const Vec3 &a = c.soup.vertices[t[0]], &b = c.soup.vertices[t[1]], &cc = c.soup.vertices[t[2]];
      const Vec3 e1 = difference(b, a), e2 = difference(cc, a), s = difference(ray.origin, a);
      const Vec3 q = cross(ray.direction, e2);
      const double det = dot(e1, q);
      if (det == 0.0) continue;
      const double u = dot(s, q) / det;
      const Vec3 w = cross(s, e1);
      const double v = dot(ray.direction, w) / det, d = dot(e2, w) / det;
      if (u >= 0 && v >= 0 && u + v <= 1 && d > 0 && d < best) best = d;
    }
    if (std::isfinite(best))
      lights.push_back(Light{{ray.origin[0] + best * ray.direction[0], ray.origin[1] + best * ray.direction[1],
                              ray.origin[2] + best * ray.direction[2], 1.0}});
  }
  return lights;
}

// The per-pixel sums of `image`'s light images (ExactLightTally's definition).
ExactLightTally summed(const ExactImage& image) {
  ExactLightTally tally;
  const std::size_t pixels = std::size_t{image.width} * image.height;
  tally.defined.assign(pixels, 0);
  tally.lit.assign(pixels, 0);
  tally.terminator.assign(pixels, 0);
  for (const ExactLightImage& l : image.lights)
    for (std::size_t p = 0; p < pixels; ++p) {
      const bool defined = l.counts[p] != kNoHit && l.counts[p] != kUndefinedCount;
      tally.defined[p] += defined ? 1 : 0;
      tally.lit[p] += l.lit[p] != 0 ? 1 : 0;
      if ((l.ambiguity[p] & kTerminator) != 0) tally.terminator[p] = 1;
    }
  return tally;
}

TEST(ExactImageManyLights, CountedTogether_EqualsEachLightAlone) {
  std::uint64_t shadowed = 0, undefined = 0, lit = 0, compared = 0;
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    const std::vector<Light> lights = lights_of(c);
    ExactImageOptions options;
    options.footprints = false;
    options.casts = c.casts;
    const ExactImage together = exact_image(c.soup, lights, c.camera, options);
    ASSERT_EQ(together.lights.size(), lights.size());
    // Without light images: their sums, made as the counts come (no image held per light).
    ExactImageOptions sums_only = options;
    sums_only.light_images = false;
    const ExactImage tallied = exact_image(c.soup, lights, c.camera, sums_only);
    EXPECT_TRUE(tallied.lights.empty());
    EXPECT_EQ(tallied.hit_triangles, together.hit_triangles);
    const ExactLightTally expected = summed(together);
    EXPECT_EQ(tallied.tally.defined, expected.defined);
    EXPECT_EQ(tallied.tally.lit, expected.lit);
    EXPECT_EQ(tallied.tally.terminator, expected.terminator);
    for (std::size_t k = 0; k < lights.size(); ++k) {
      const ExactImage alone = exact_image(c.soup, std::span<const Light>(&lights[k], 1), c.camera, options);
      EXPECT_EQ(together.hit_triangles, alone.hit_triangles);
      const ExactLightImage& a = together.lights[k];
      const ExactLightImage& b = alone.lights[0];
      for (std::size_t p = 0; p < a.counts.size(); ++p) {
        EXPECT_EQ(a.counts[p], b.counts[p]) << "light " << k << " pixel " << p;
        EXPECT_EQ(a.lit[p], b.lit[p]) << "light " << k << " pixel " << p;
        EXPECT_EQ(a.ambiguity[p], b.ambiguity[p]) << "light " << k << " pixel " << p;
        if (b.counts[p] == kUndefinedCount) ++undefined;
        else if (b.counts[p] != kNoHit) (b.counts[p] == 0 ? lit : shadowed) += 1;
      }
      compared += a.counts.size();
    }
  }
  std::cout << compared << " pixel verdicts compared: " << lit << " lit, " << shadowed << " shadowed, " << undefined
            << " undefined\n";
  EXPECT_GT(shadowed, 10000u);
  EXPECT_GT(undefined, 100u);  // touching segments (zero signs) are among them
}

}  // namespace
