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

namespace shadowcert {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// Predicate calls one shrink may spend: each renders the candidate and images it exactly
// (tens of ms on llvmpipe at 64x48), so a 100-triangle case shrinks in well under a minute.
constexpr std::size_t kMaxShrinkTests = 300;

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

void tally(GlCampaignTally& t, const MethodRun& run, const CampaignCase& c) {
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
    ++t.failures_by_family[static_cast<std::size_t>(c.kind.family)];
    ++t.failures_by_placement[static_cast<std::size_t>(c.kind.light)];
  }
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
    const CampaignCase c = campaign_case(options.seed, i, options.triangles);
    const SceneComparison comparison = compare_scene(
        campaign_view_scene(campaign_view(c, options.width, options.height)), options.methods, comparison_options(options));
    result.exact_seconds += comparison.exact.stats.seconds + comparison.rounded_seconds;
    for (std::size_t m = 0; m < options.methods.size(); ++m) {
      tally(result.methods[m], comparison.runs[m], c);
      if (const std::optional<GlFailureKind> kind = failure_of(comparison.runs[m]))
        result.failures.push_back({i, m, *kind});
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
    result.shrunk.push_back(shrink_gl_failure(options, f));
  }
  result.shrink_seconds = seconds_since(shrink_start);
  return result;
}

GlReproducer write_gl_reproducer(const fs::path& dir, const GlCampaignOptions& options, const ShrunkGlFailure& shrunk) {
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
