#include "cli/track_command.h"

#include <fmt/core.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cli/exit_code.h"
#include "contour/tracking_variant.h"
#include "core/box.h"
#include "core/input_error.h"
#include "io/light_path_file.h"
#include "io/output_file.h"
#include "io/scene_input.h"
#include "pipeline/silhouette_tracking.h"
#include "scene/light_orbit.h"

namespace shadowcert::cli {
namespace {

// Frames of the orbit when --frames is not given: one light per degree.
constexpr std::int64_t kDefaultOrbitFrames = 360;
// The period `--variant all` gives periodic:T.
constexpr std::uint32_t kAllVariantsPeriod = 10;

struct TrackOptions {
  std::string input;
  std::int64_t frames = 0;
  bool frames_given = false;
  std::string variants = "all";
  std::optional<double> orbit_radius, orbit_height;
  double orbit_turns = 1.0;
  std::string path_file;
  bool per_frame = false;
  std::string json_file;
};

std::vector<TrackingVariant> variants_option(const std::string& list) {
  std::vector<TrackingVariant> variants;
  const auto add = [&](const TrackingVariant& v) {
    if (std::find(variants.begin(), variants.end(), v) == variants.end()) variants.push_back(v);
  };
  std::size_t start = 0;
  while (start <= list.size()) {
    const std::size_t comma = std::min(list.find(',', start), list.size());
    const std::string name = list.substr(start, comma - start);
    start = comma + 1;
    if (name == "all") {
      for (const TrackingVariant& v : {TrackingVariant{TrackingSearch::full, 0}, TrackingVariant{TrackingSearch::one_way, 0},
                                       TrackingVariant{TrackingSearch::continue_search, 0},
                                       TrackingVariant{TrackingSearch::periodic, kAllVariantsPeriod}})
        add(v);
      continue;
    }
    const std::optional<TrackingVariant> variant = parse_tracking_variant(name);
    if (variant) {
      add(*variant);
      continue;
    }
    if (name.starts_with("periodic:"))
      throw CLI::ValidationError("--variant", "periodic:T needs a whole number T >= 1, got '" + name.substr(9) + "'");
    throw CLI::ValidationError("--variant", "unknown variant '" + name +
                                                "': use full, one-way, continue, periodic:T (T >= 1), all, or a comma-separated list");
  }
  return variants;
}

struct LightPath {
  std::vector<Light> lights;
  nlohmann::json description;
  std::string summary;
};

LightPath light_path(const TrackOptions& options, const Box& bounds) {
  if (options.frames < 0 || (options.frames == 0 && options.frames_given))
    throw CLI::ValidationError("--frames", "must be at least 1");
  LightPath path;
  if (!options.path_file.empty()) {
    const std::vector<Light> file = read_light_path_file(options.path_file);
    const std::size_t frames = options.frames > 0 ? static_cast<std::size_t>(options.frames) : file.size();
    for (std::size_t i = 0; i < frames; ++i) path.lights.push_back(file[i % file.size()]);
    path.description = {{"kind", "file"}, {"file", options.path_file}, {"lights", file.size()}};
    path.summary = fmt::format("path {} ({} light{}{})", options.path_file, file.size(), file.size() == 1 ? "" : "s",
                               frames > file.size() ? ", repeated" : "");
    return path;
  }
  LightOrbit orbit = default_light_orbit(bounds);
  if (options.orbit_radius) {
    if (!(std::isfinite(*options.orbit_radius) && *options.orbit_radius > 0.0))
      throw CLI::ValidationError("--orbit-radius", "must be positive and finite");
    orbit.radius = *options.orbit_radius;
  }
  if (options.orbit_height) {
    if (!std::isfinite(*options.orbit_height)) throw CLI::ValidationError("--orbit-height", "must be finite");
    orbit.height = *options.orbit_height;
  }
  if (!std::isfinite(options.orbit_turns)) throw CLI::ValidationError("--orbit-turns", "must be finite");
  orbit.turns = options.orbit_turns;
  const std::size_t frames = options.frames > 0 ? static_cast<std::size_t>(options.frames) : kDefaultOrbitFrames;
  path.lights = orbit_lights(orbit, frames);
  for (const Light& light : path.lights)
    if (!light.defined()) throw CLI::ValidationError("--orbit-radius", "the orbit's lights leave the finite doubles");
  path.description = {{"kind", "orbit"},
                      {"center", orbit.center},
                      {"radius", orbit.radius},
                      {"height", orbit.height},
                      {"turns", orbit.turns}};
  path.summary = fmt::format("orbit around ({:.6g}, {:.6g}, {:.6g}), radius {:.6g}, height {:.6g}, {:.6g} turn{}",
                             orbit.center[0], orbit.center[1], orbit.center[2], orbit.radius, orbit.height, orbit.turns,
                             orbit.turns == 1.0 ? "" : "s");
  return path;
}

nlohmann::json summary_json(const TrackingSummary& s) {
  return {{"frames", s.frames},
          {"mean_miss_rate", s.mean_miss_rate},
          {"max_miss_rate", s.max_miss_rate},
          {"frames_with_misses", s.frames_with_misses},
          {"missed", s.missed},
          {"false_positives", s.false_positives},
          {"oldest_miss", s.oldest_miss},
          {"mean_edges_checked", s.mean_edges_checked},
          {"mean_found", s.mean_found},
          {"mean_exact", s.mean_exact},
          {"mean_ms", s.mean_milliseconds}};
}

nlohmann::json frame_json(std::size_t i, const TrackingFrameRecord& f) {
  return {{"frame", i},
          {"edges_checked", f.edges_checked},
          {"faces_evaluated", f.faces_evaluated},
          {"ms", f.milliseconds},
          {"full_search", f.full_search},
          {"found", f.found},
          {"exact", f.exact},
          {"missed", f.missed},
          {"false_positives", f.false_positives},
          {"miss_rate", f.miss_rate()},
          {"oldest_miss", f.oldest_miss}};
}

void print_summary_table(const TrackingComparison& comparison) {
  fmt::print("{:<14}{:>11}{:>11}{:>15}{:>9}{:>11}{:>8}{:>15}{:>13}{:>13}{:>10}\n", "variant", "mean miss", "max miss",
             "frames missed", "missed", "false pos", "oldest", "checked/frame", "found/frame", "exact/frame", "ms/frame");
  for (const VariantTracking& v : comparison.variants) {
    const TrackingSummary s = v.summary();
    fmt::print("{:<14}{:>10.4f}%{:>10.4f}%{:>15}{:>9}{:>11}{:>8}{:>15.1f}{:>13.1f}{:>13.1f}{:>10.4f}\n",
               tracking_variant_name(v.variant), 100.0 * s.mean_miss_rate, 100.0 * s.max_miss_rate, s.frames_with_misses,
               s.missed, s.false_positives, s.oldest_miss, s.mean_edges_checked, s.mean_found, s.mean_exact,
               s.mean_milliseconds);
  }
}

void print_frame_table(const VariantTracking& v, const std::vector<Light>& lights) {
  fmt::print("\n{} per frame\n", tracking_variant_name(v.variant));
  fmt::print("{:>6}  {:<36}{:>10}{:>8}{:>8}{:>8}{:>8}{:>10}{:>8}{:>10}\n", "frame", "light", "checked", "found", "exact",
             "missed", "false+", "miss", "oldest", "ms");
  for (std::size_t i = 0; i < v.frames.size(); ++i) {
    const TrackingFrameRecord& f = v.frames[i];
    const auto& l = lights[i].position;
    fmt::print("{:>6}{} {:<36}{:>10}{:>8}{:>8}{:>8}{:>8}{:>9.3f}%{:>8}{:>10.4f}\n", i, f.full_search ? "*" : " ",
               fmt::format("({:.4g}, {:.4g}, {:.4g}, {:g})", l[0], l[1], l[2], l[3]), f.edges_checked, f.found, f.exact,
               f.missed, f.false_positives, 100.0 * f.miss_rate(), f.oldest_miss, f.milliseconds);
  }
}

int run_track(const TrackOptions& options) {
  const Scene scene = load_scene_or_mesh(options.input);
  std::vector<TrackingMesh> meshes;
  nlohmann::json mesh_json = nlohmann::json::array();
  std::vector<Vec3> corners;
  std::vector<std::string> lines;
  for (const SceneMesh& mesh : scene.meshes) {
    if (!mesh.casts) {
      lines.push_back(fmt::format("  mesh {}: receives only (\"casts\": false), not tracked", mesh.name));
      mesh_json.push_back({{"name", mesh.name}, {"casts", false}, {"tracked", false}});
      continue;
    }
    if (mesh.soup.triangles.empty()) continue;
    const Box box = used_vertex_box(mesh.soup);
    corners.push_back(box.lo);
    corners.push_back(box.hi);
    meshes.push_back(tracking_mesh(mesh.name, mesh.soup));
    const TrackingMesh& m = meshes.back();
    nlohmann::json entry = {{"name", m.name},           {"casts", true},   {"tracked", m.tracked()},
                            {"triangles", m.triangles}, {"edges", m.table.size()}, {"qualification", m.qualification}};
    if (m.tracked()) {
      entry["concave_edges"] = m.graph->concave_edges.size();
      entry["border_edges"] = m.graph->border_edges.size();
      lines.push_back(fmt::format("  mesh {}: {} triangles, {} edges ({} concave, {} border): tracked", m.name, m.triangles,
                                  m.table.size(), m.graph->concave_edges.size(), m.graph->border_edges.size()));
    } else {
      lines.push_back(fmt::format("  mesh {}: {} triangles, {} edges: not tracked ({}): exact full search only", m.name,
                                  m.triangles, m.table.size(), m.qualification));
    }
    mesh_json.push_back(std::move(entry));
  }
  if (meshes.empty()) throw InputError(options.input, "no casting triangle to track");

  const LightPath path = light_path(options, bounding_box(corners));
  const std::vector<TrackingVariant> variants = variants_option(options.variants);
  const auto tracked = static_cast<std::size_t>(
      std::count_if(meshes.begin(), meshes.end(), [](const TrackingMesh& m) { return m.tracked(); }));
  // With nothing to track only the exact full search runs.
  const TrackingComparison comparison =
      compare_tracking(meshes, path.lights, tracked > 0 ? variants : std::vector<TrackingVariant>{});

  fmt::print("{}: {} casting mesh{}, {} tracked\n", options.input, meshes.size(), meshes.size() == 1 ? "" : "es", tracked);
  for (const std::string& line : lines) fmt::print("{}\n", line);
  fmt::print("light path: {}, {} frames\n\n", path.summary, path.lights.size());
  if (tracked == 0)
    fmt::print("no mesh qualifies for tracking (an oriented 2-manifold, contour/smooth_caster.h): only the exact full search ran\n");
  else
    print_summary_table(comparison);
  double tracked_ms = 0.0, fallback_ms = 0.0, tracked_edges = 0.0, fallback_edges = 0.0;
  for (const ExactSearchFrame& f : comparison.exact) {
    tracked_ms += f.tracked_milliseconds;
    fallback_ms += f.fallback_milliseconds;
    tracked_edges += static_cast<double>(f.tracked_edges);
    fallback_edges += static_cast<double>(f.fallback_edges);
  }
  const auto n = static_cast<double>(comparison.exact.size());
  std::vector<std::string> parts;
  if (tracked > 0)
    parts.push_back(fmt::format("tracked meshes {:.4f} ms/frame ({:.1f} silhouette edges)", tracked_ms / n, tracked_edges / n));
  if (tracked < meshes.size())
    parts.push_back(fmt::format("untracked meshes {:.4f} ms/frame ({:.1f} silhouette edges)", fallback_ms / n, fallback_edges / n));
  fmt::print("exact full search (exact/edge_multiplicity.h): {}\n", fmt::join(parts, ", "));
  if (options.per_frame)
    for (const VariantTracking& v : comparison.variants) print_frame_table(v, path.lights);

  if (!options.json_file.empty()) {
    nlohmann::json report = {{"input", options.input}, {"frames", path.lights.size()}, {"path", path.description},
                             {"meshes", mesh_json}};
    nlohmann::json lights = nlohmann::json::array();
    for (const Light& l : path.lights) lights.push_back(l.position);
    report["lights"] = std::move(lights);
    nlohmann::json variant_json = nlohmann::json::array();
    for (const VariantTracking& v : comparison.variants) {
      nlohmann::json frames = nlohmann::json::array();
      for (std::size_t i = 0; i < v.frames.size(); ++i) frames.push_back(frame_json(i, v.frames[i]));
      variant_json.push_back({{"variant", tracking_variant_name(v.variant)}, {"summary", summary_json(v.summary())},
                              {"frames", std::move(frames)}});
    }
    report["variants"] = std::move(variant_json);
    nlohmann::json exact_frames = nlohmann::json::array();
    for (std::size_t i = 0; i < comparison.exact.size(); ++i) {
      const ExactSearchFrame& f = comparison.exact[i];
      exact_frames.push_back({{"frame", i},
                              {"tracked_ms", f.tracked_milliseconds},
                              {"tracked_edges", f.tracked_edges},
                              {"untracked_ms", f.fallback_milliseconds},
                              {"untracked_edges", f.fallback_edges}});
    }
    report["exact"] = {{"mean_tracked_ms", tracked_ms / n},
                       {"mean_untracked_ms", fallback_ms / n},
                       {"mean_tracked_edges", tracked_edges / n},
                       {"mean_untracked_edges", fallback_edges / n},
                       {"frames", std::move(exact_frames)}};
    write_json_file(options.json_file, report);
  }
  return kExitOk;
}

}  // namespace

void add_track_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<TrackOptions>();
  CLI::App* cmd = app.add_subcommand(
      "track", "Silhouette tracking (Chen and Tsai) along a light path, held to the exact silhouette (docs/smoothies.md)");
  cmd->add_option("input", options->input, "Mesh file (.obj .off .ply .stl) or scene (.json)")->required();
  cmd->add_option("--frames", options->frames,
                  "Frames (default: 360 on the orbit; the path's lights with --path, repeated when N exceeds them)");
  cmd->add_option("--variant", options->variants,
                  "full, one-way, continue, periodic:T (full search every T frames), or all "
                  "(= full,one-way,continue,periodic:10); a comma-separated list")
      ->capture_default_str();
  CLI::Option* radius = cmd->add_option("--orbit-radius", options->orbit_radius,
                                        "Orbit radius around the vertical axis (default: 2 x the casters' half diagonal)");
  CLI::Option* height = cmd->add_option("--orbit-height", options->orbit_height,
                                        "Orbit height above the casters' bounds centre (default: half their half diagonal)");
  CLI::Option* turns = cmd->add_option("--orbit-turns", options->orbit_turns, "Turns of the orbit over the frames")
                           ->capture_default_str();
  cmd->add_option("--path", options->path_file, "Light path file: one light \"x y z w\" per line, instead of the orbit")
      ->excludes(radius)
      ->excludes(height)
      ->excludes(turns);
  cmd->add_flag("--per-frame", options->per_frame, "Also print every variant's table frame by frame");
  cmd->add_option("--json", options->json_file, "Write the per-frame records and summaries as JSON to FILE");
  cmd->callback([options, cmd, &exit_code] {
    options->frames_given = cmd->count("--frames") > 0;
    exit_code = run_track(*options);
  });
}

}  // namespace shadowcert::cli
