#include "campaign/gl_campaign.h"

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>

#include "core/near_plane.h"
#include "io/output_file.h"
#include "io/scene_input.h"
#include "io/soup_file.h"
#include "campaign/soup_shrinker.h"
#include "campaign/window_comparison.h"
#include "scene/merged_soup.h"

namespace shadowcert {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// Predicate calls one shrink may spend: each renders the candidate and images it exactly
// (tens of ms on llvmpipe at 64x48), so a 100-triangle case shrinks in well under a minute.
constexpr std::size_t kMaxShrinkTests = 300;
// A hard scene's hard-error failure is shrunk on the pixels within this distance (in pixels,
// each way) of its first hard pixel, a window of 2 kShrinkReach + 1 pixels square
// (campaign/window_comparison.h): the failure is that pixel's, and the window's exact image
// costs milliseconds where the whole image at 1024x768 costs seconds.
constexpr std::uint32_t kShrinkReach = 4;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// How a robust method failed: an open volume first (its counts are then no counts), else hard
// errors; nullopt when it did not fail (the shadow map never does).
std::optional<GlFailureKind> failure_of(const MethodRun& run) {
  if (!run.failed()) return std::nullopt;
  return run.closed() == false ? GlFailureKind::closure : GlFailureKind::hard_errors;
}

std::string_view failure_name(GlFailureKind kind) { return kind == GlFailureKind::closure ? "closure" : "hard_errors"; }

// The GL comparison of the campaign: z-fail (the robust default), the options' signs, no
// timed frames.
SceneComparisonOptions comparison_options(const GlCampaignOptions& options) {
  SceneComparisonOptions o;
  o.method_options.sign = options.sign;
  return o;
}

// Which light failed first, and its first hard pixel (column, row): what a hard scene's
// failure is shrunk around.
void locate(GlCampaignFailure& f, const MethodRun& run, std::uint32_t width) {
  for (std::size_t k = 0; k < run.lights.size(); ++k) {
    const LightRun& l = run.lights[k];
    const bool open = !l.closure || !l.closure->closed;
    if (f.kind == GlFailureKind::closure ? !open : l.comparison.hard_errors == 0) continue;
    f.light = k;
    const auto& v = l.comparison.verdicts;
    const auto hard = std::find(v.begin(), v.end(), PixelVerdict::hard_error);
    if (hard != v.end()) {
      const auto p = static_cast<std::uint64_t>(hard - v.begin());
      f.pixel = {static_cast<std::uint32_t>(p % width), static_cast<std::uint32_t>(p / width)};
    }
    return;
  }
}

void tally(GlCampaignTally& t, const MethodRun& run, const CampaignCase* c, const std::vector<HardPart>& parts) {
  const bool open = run.closed() == false;
  const std::uint64_t hard = run.sum(&PixelComparison::hard_errors);
  t.closure_failures += open ? 1 : 0;
  t.hard_errors += hard > 0 ? 1 : 0;
  t.hard_error_pixels += hard;
  t.ambiguous_pixels += run.sum(&PixelComparison::ambiguous);
  t.agree_pixels += run.sum(&PixelComparison::agree);
  bool overflow = false;
  for (const LightRun& l : run.lights) {
    overflow = overflow || !l.capacity_error.empty();
    t.volume_triangles += l.volume_triangles;
  }
  t.capacity_errors += overflow ? 1 : 0;
  if (run.failed()) {
    ++t.failures;
    if (c != nullptr) {
      ++t.failures_by_family[static_cast<std::size_t>(c->kind.family)];
      ++t.failures_by_placement[static_cast<std::size_t>(c->kind.light)];
    }
    for (HardPart p : parts) ++t.failures_by_part[static_cast<std::size_t>(p)];
  }
}

// Whether `run`, one light of one method, fails as `kind` says (an open volume; hard errors on
// a closed one, as failure_of orders them).
bool fails_as(const LightRun& run, GlFailureKind kind) {
  const bool open = !run.closure || !run.closure->closed;
  return kind == GlFailureKind::closure ? open : !open && run.comparison.hard_errors > 0;
}

std::vector<std::array<std::uint32_t, 2>> hard_pixels(const LightRun& run, std::uint32_t width) {
  std::vector<std::array<std::uint32_t, 2>> pixels;
  for (std::size_t p = 0; p < run.comparison.verdicts.size(); ++p)
    if (run.comparison.verdicts[p] == PixelVerdict::hard_error)
      pixels.push_back({static_cast<std::uint32_t>(p % width), static_cast<std::uint32_t>(p / width)});
  return pixels;
}

// A hard scene's failure shrunk (shrink_scene_failure) and recorded with its parts.
ShrunkGlFailure shrink_hard_failure(const GlCampaignOptions& options, const GlCampaignFailure& failure) {
  ShrunkGlFailure out;
  out.failure = failure;
  const HardSceneCase h = hard_scene_case(options.seed, failure.index, options.width, options.height);
  out.parts = h.parts;
  SceneShrink shrunk = shrink_scene_failure(h.scene, 0, failure.light, options.methods[failure.method], failure.kind,
                                            failure.pixel, options.sign);
  out.scene = std::move(shrunk.scene);
  out.pixels = std::move(shrunk.pixels);
  out.window = shrunk.window;
  out.original_triangles = shrunk.original_triangles;
  out.tests = shrunk.tests;
  out.minimal = shrunk.minimal;
  return out;
}

ShrunkGlFailure shrink_gl_failure(const GlCampaignOptions& options, const GlCampaignFailure& failure) {
  ShrunkGlFailure out;
  out.failure = failure;
  out.original = campaign_case(options.seed, failure.index, options.triangles);
  out.view = campaign_view(out.original, options.width, options.height);
  out.original_triangles = out.view.soup.triangles.size();
  const std::vector<gpu::ShadowMethod> method{options.methods[failure.method]};
  CampaignView candidate = out.view;
  // The floor and camera stay the case's: the failure is a property of that picture.
  const auto still_fails = [&](const Soup& soup) {
    candidate.soup = soup;
    const SceneComparison c = compare_scene(campaign_view_scene(candidate), method, comparison_options(options));
    return failure_of(c.runs.front()) == failure.kind;
  };
  const ShrinkResult shrunk = shrink_soup(out.view.soup, still_fails, kMaxShrinkTests);
  out.view.soup = shrunk.soup;
  out.tests = shrunk.tests;
  out.minimal = shrunk.minimal;
  return out;
}

nlohmann::json vec_json(const Vec3& v) { return nlohmann::json::array({v[0], v[1], v[2]}); }

bool same_soup(const Soup& a, const Soup& b) { return a.vertices == b.vertices && a.triangles == b.triangles; }

bool same_camera(const Camera& a, const Camera& b) {
  return a.eye == b.eye && a.target == b.target && a.up == b.up && a.fov_y_degrees == b.fov_y_degrees &&
         a.width == b.width && a.height == b.height;
}

}  // namespace

std::string gl_run_name(gpu::ShadowMethod method) { return "gl-" + std::string(gpu::shadow_method_name(method)); }

std::string_view gl_scene_source_name(GlSceneSource source) {
  return source == GlSceneSource::hard ? "hard" : "soups";
}

SceneShrink shrink_scene_failure(const Scene& scene, std::size_t held_mesh, std::size_t light,
                                 gpu::ShadowMethod method, GlFailureKind kind, std::array<std::uint32_t, 2> pixel,
                                 gpu::SignMode sign) {
  if (held_mesh >= scene.meshes.size() || light >= scene.lights.size())
    throw std::invalid_argument("shrink_scene_failure: no such mesh or light");
  const std::uint32_t width = scene.camera.width, height = scene.camera.height;
  if (pixel[0] >= width || pixel[1] >= height) throw std::invalid_argument("shrink_scene_failure: pixel outside the image");
  SceneShrink out;
  Soup casters;
  for (std::size_t m = 0; m < scene.meshes.size(); ++m)
    if (m != held_mesh) append_soup(casters, scene.meshes[m].soup);
  casters.normals.clear();
  out.scene.meshes.resize(2);
  out.scene.meshes[0] = scene.meshes[held_mesh];
  out.scene.meshes[1].name = "casters";
  out.scene.meshes[1].soup = casters;
  out.scene.lights = {scene.lights[light]};
  out.scene.camera = scene.camera;
  out.original_triangles = casters.triangles.size();
  gpu::ShadowMethodOptions method_options;
  method_options.sign = sign;
  const auto window_around = [&](std::uint32_t x, std::uint32_t y, std::uint32_t reach) {
    const std::uint32_t x0 = x > reach ? x - reach : 0, y0 = y > reach ? y - reach : 0;
    return PixelWindow{x0, y0, std::min(x + reach + 1, width) - x0, std::min(y + reach + 1, height) - y0};
  };
  // An open volume needs no pixel: the window is one, for the exact image's sake.
  out.window = kind == GlFailureKind::closure ? PixelWindow{0, 0, 1, 1} : window_around(pixel[0], pixel[1], kShrinkReach);
  Scene candidate = out.scene;
  const auto still_fails = [&](const Soup& soup) {
    candidate.meshes[1].soup = soup;
    return fails_as(compare_in_window(candidate, method, 0, out.window, method_options), kind);
  };
  const ShrinkResult shrunk = shrink_soup(casters, still_fails, kMaxShrinkTests);
  out.scene.meshes[1].soup = shrunk.soup;
  out.tests = shrunk.tests;
  out.minimal = shrunk.minimal;
  if (kind == GlFailureKind::hard_errors) {
    const LightRun run = compare_in_window(out.scene, method, 0, out.window, method_options);
    out.pixels = hard_pixels(run, width);
    if (!out.pixels.empty()) out.window = window_around(out.pixels.front()[0], out.pixels.front()[1], 0);
  }
  return out;
}

Scene gl_campaign_scene(const GlCampaignOptions& options, std::uint64_t index) {
  if (options.scenes == GlSceneSource::hard) return hard_scene_case(options.seed, index, options.width, options.height).scene;
  return campaign_view_scene(campaign_view(campaign_case(options.seed, index, options.triangles), options.width, options.height));
}

Scene campaign_view_scene(const CampaignView& view) {
  Scene scene;
  scene.meshes.resize(2);
  scene.meshes[0].name = "soup";
  scene.meshes[0].soup = view.soup;
  scene.meshes[1].name = "floor";
  scene.meshes[1].soup = view.floor;
  scene.lights = {view.light};
  scene.camera = view.camera;
  scene.camera = camera_fitted_to(scene);  // a snapped soup at 2^17 needs a far near plane
  return scene;
}

GlCampaignResult run_gl_campaign(const GlCampaignOptions& options) {
  if (options.methods.empty()) throw std::invalid_argument("run_gl_campaign: no method");
  if (options.width == 0 || options.height == 0) throw std::invalid_argument("run_gl_campaign: empty image");
  if (!valid_case_shard(options.shard))
    throw std::invalid_argument("run_gl_campaign: a shard needs count >= 1 and index < count");
  GlCampaignResult result;
  result.methods.resize(options.methods.size());
  const auto start = Clock::now();
  const std::uint64_t shard_cases = shard_case_count(options.cases, options.shard);
  for (std::uint64_t j = 0; j < shard_cases; ++j) {
    const std::uint64_t i = shard_case_index(options.shard, j);
    std::optional<CampaignCase> c;
    Scene scene;
    std::vector<HardPart> parts;
    if (options.scenes == GlSceneSource::hard) {
      HardSceneCase h = hard_scene_case(options.seed, i, options.width, options.height);
      scene = std::move(h.scene);
      parts = std::move(h.parts);
      for (HardPart p : parts) ++result.cases_by_part[static_cast<std::size_t>(p)];
      result.cases_light_on_plane += h.first_light_on_plane ? 1 : 0;
      result.cases_edge_on += h.edge_on_view ? 1 : 0;
    } else {
      c = campaign_case(options.seed, i, options.triangles);
      scene = campaign_view_scene(campaign_view(*c, options.width, options.height));
    }
    const SceneComparison comparison = compare_scene(scene, options.methods, comparison_options(options));
    result.exact_seconds += comparison.exact.stats.seconds + comparison.rounded_seconds;
    for (std::size_t m = 0; m < options.methods.size(); ++m) {
      tally(result.methods[m], comparison.runs[m], c ? &*c : nullptr, parts);
      if (const std::optional<GlFailureKind> kind = failure_of(comparison.runs[m])) {
        GlCampaignFailure f{i, m, *kind};
        locate(f, comparison.runs[m], options.width);
        result.failures.push_back(f);
      }
    }
    ++result.cases;
    if (options.progress != nullptr) options.progress->fetch_add(1);
  }
  result.seconds = seconds_since(start);

  const auto shrink_start = Clock::now();
  std::vector<std::size_t> shrunk_per_method(options.methods.size(), 0);
  for (const GlCampaignFailure& f : result.failures) {
    if (shrunk_per_method[f.method] >= options.max_shrunk_per_method) continue;
    ++shrunk_per_method[f.method];
    result.shrunk.push_back(options.scenes == GlSceneSource::hard ? shrink_hard_failure(options, f)
                                                                   : shrink_gl_failure(options, f));
  }
  result.shrink_seconds = seconds_since(shrink_start);
  return result;
}

namespace {

std::string part_list(const std::vector<HardPart>& parts) {
  std::string s;
  for (HardPart p : parts) s += (s.empty() ? "" : ", ") + std::string(hard_part_name(p));
  return s;
}

// A hard scene's shrunk failure: NAME.json with the floor and the casters as OFF files, the one
// light and the camera with its near plane (held while shrinking: the failure is that picture's).
GlReproducer write_hard_reproducer(const fs::path& dir, const GlCampaignOptions& options, const ShrunkGlFailure& shrunk) {
  const gpu::ShadowMethod method = options.methods[shrunk.failure.method];
  const std::string name = fmt::format("{}-hard-s{}-c{}", gl_run_name(method), options.seed, shrunk.failure.index);
  GlReproducer r;
  r.method = gl_run_name(method);
  r.case_index = shrunk.failure.index;
  r.failure = failure_name(shrunk.failure.kind);
  r.original_triangles = shrunk.original_triangles;
  r.triangles = shrunk.scene.meshes[1].soup.triangles.size();
  r.json = dir / (name + ".json");
  create_parent_directories(r.json);
  write_soup(dir / (name + ".casters.off"), shrunk.scene.meshes[1].soup);
  write_soup(dir / (name + ".floor.off"), shrunk.scene.meshes[0].soup);
  const Camera& camera = shrunk.scene.camera;
  const Light& light = shrunk.scene.lights.front();
  std::string pixels;
  for (const auto& p : shrunk.pixels) pixels += fmt::format("{}({}, {})", pixels.empty() ? "" : ", ", p[0], p[1]);
  const nlohmann::json scene{
      {"description",
       fmt::format("shadowcert fuzz --gl --gl-scenes hard reproducer: {} fails ({}) on scene {} of seed {} at {}x{} "
                   "(parts: {}; light {} of the scene; {} triangles shrunk to {}{}), the floor, light and camera "
                   "held (docs/campaign.md)",
                   r.method, r.failure, r.case_index, options.seed, options.width, options.height,
                   part_list(shrunk.parts), shrunk.failure.light, r.original_triangles, r.triangles,
                   pixels.empty() ? std::string() : "; hard pixels (column, row): " + pixels)},
      {"meshes",
       nlohmann::json::array({{{"name", "floor"}, {"file", name + ".floor.off"}},
                              {{"name", "casters"}, {"file", name + ".casters.off"}}})},
      {"lights", nlohmann::json::array({nlohmann::json::array(
                     {light.position[0], light.position[1], light.position[2], light.position[3]})})},
      {"camera",
       {{"eye", vec_json(camera.eye)},
        {"target", vec_json(camera.target)},
        {"up", vec_json(camera.up)},
        {"fov_y_deg", camera.fov_y_degrees},
        {"size", nlohmann::json::array({camera.width, camera.height})},
        {"near", camera.near_plane}}}};
  write_json_file(r.json, scene);
  if (!shrunk.pixels.empty()) {
    // tests/regressions/README.md: "column row" per line, light 0 (the scene's only light).
    std::string lines;
    for (const auto& p : shrunk.pixels) lines += fmt::format("{} {}\n", p[0], p[1]);
    write_text_file(dir / (name + ".pixels"), lines);
  }
  r.command = fmt::format("shadowcert diff {} --methods {}{}", r.json.string(), gpu::shadow_method_name(method),
                          options.sign == gpu::SignMode::float32 ? " --sign float" : "");
  const Scene back = load_scene_or_mesh(r.json);
  const bool same = back.meshes.size() == 2 && same_soup(back.meshes[0].soup, shrunk.scene.meshes[0].soup) &&
                    same_soup(back.meshes[1].soup, shrunk.scene.meshes[1].soup) && back.lights.size() == 1 &&
                    back.lights[0].position == light.position && same_camera(back.camera, camera) &&
                    back.camera.near_plane == camera.near_plane;
  r.replayed = same && failure_of(compare_scene(back, {method}, comparison_options(options)).runs.front()) ==
                           shrunk.failure.kind;
  return r;
}

}  // namespace

GlReproducer write_gl_reproducer(const fs::path& dir, const GlCampaignOptions& options, const ShrunkGlFailure& shrunk) {
  if (options.scenes == GlSceneSource::hard) return write_hard_reproducer(dir, options, shrunk);
  const gpu::ShadowMethod method = options.methods[shrunk.failure.method];
  const std::string name = fmt::format("{}-s{}-c{}", gl_run_name(method), options.seed, shrunk.failure.index);
  GlReproducer r;
  r.method = gl_run_name(method);
  r.case_index = shrunk.failure.index;
  r.failure = failure_name(shrunk.failure.kind);
  r.original_triangles = shrunk.original_triangles;
  r.triangles = shrunk.view.soup.triangles.size();
  r.json = dir / (name + ".json");
  create_parent_directories(r.json);
  // OFF with 17 significant digits (io/soup_file.h): read back bit for bit.
  write_soup(dir / (name + ".soup.off"), shrunk.view.soup);
  write_soup(dir / (name + ".floor.off"), shrunk.view.floor);
  const Camera& camera = shrunk.view.camera;
  const Light& light = shrunk.view.light;
  const nlohmann::json scene{
      {"description",
       fmt::format("shadowcert fuzz --gl reproducer: {} fails ({}) on case {} of seed {} ({} soup, {} light, {} "
                   "triangles shrunk to {}), in the case's unit frame with the campaign view's floor and camera "
                   "(docs/campaign.md)",
                   r.method, r.failure, r.case_index, options.seed, family_name(shrunk.original.kind.family),
                   placement_name(shrunk.original.kind.light), r.original_triangles, r.triangles)},
      {"meshes",
       nlohmann::json::array({{{"name", "soup"}, {"file", name + ".soup.off"}},
                              {{"name", "floor"}, {"file", name + ".floor.off"}}})},
      {"lights", nlohmann::json::array({nlohmann::json::array(
                     {light.position[0], light.position[1], light.position[2], light.position[3]})})},
      {"camera",
       {{"eye", vec_json(camera.eye)},
        {"target", vec_json(camera.target)},
        {"up", vec_json(camera.up)},
        {"fov_y_deg", camera.fov_y_degrees},
        {"size", nlohmann::json::array({camera.width, camera.height})}}}};
  write_json_file(r.json, scene);
  r.command = fmt::format("shadowcert diff {} --methods {}{}", r.json.string(), gpu::shadow_method_name(method),
                          options.sign == gpu::SignMode::float32 ? " --sign float" : "");

  // Read back as `diff` reads it, then compared as `diff` compares it.
  const Scene back = load_scene_or_mesh(r.json);
  const bool same = back.meshes.size() == 2 && same_soup(back.meshes[0].soup, shrunk.view.soup) &&
                    same_soup(back.meshes[1].soup, shrunk.view.floor) && back.lights.size() == 1 &&
                    back.lights[0].position == light.position && same_camera(back.camera, camera);
  r.replayed = same && failure_of(compare_scene(back, {method}, comparison_options(options)).runs.front()) ==
                           shrunk.failure.kind;
  return r;
}

}  // namespace shadowcert
