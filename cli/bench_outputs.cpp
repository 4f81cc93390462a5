#include "cli/bench_outputs.h"

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include "cli/diff_report.h"

namespace shadowcert::cli {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// ------------------------------------------------------------------ figures from the JSON

// The value at `path` (keys), or nullopt where a key is missing or a value null.
std::optional<double> number_at(const json& j, std::initializer_list<const char*> path) {
  const json* at = &j;
  for (const char* key : path) {
    if (!at->is_object() || !at->contains(key)) return std::nullopt;
    at = &(*at)[key];
  }
  if (!at->is_number()) return std::nullopt;
  return at->get<double>();
}

std::string thousands(double value) {
  const auto n = static_cast<long long>(std::llround(value));
  std::string digits = std::to_string(n < 0 ? -n : n);
  std::string out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  if (n < 0) out.insert(out.begin(), '-');
  return out;
}

std::string count_text(std::optional<double> v) { return v ? thousands(*v) : "-"; }

std::string ms_text(std::optional<double> v) {
  if (!v) return "-";
  if (*v < 10.0) return fmt::format("{:.2f}", *v);
  if (*v < 100.0) return fmt::format("{:.1f}", *v);
  return fmt::format("{:.0f}", *v);
}

std::string error_text(std::optional<double> v) { return v ? fmt::format("{:.4f}", *v) : "-"; }

std::string signed_text(std::optional<double> v) { return v ? fmt::format("{:+.4f}", *v) : "-"; }

std::string closed_text(const json& run) {
  const json& c = run.at("error").at("closed");
  return c.is_null() ? "-" : c.get<bool>() ? "yes" : "NO";
}

double frame_ms(const json& run) { return number_at(run, {"time", "frame_ms", "median"}).value_or(0.0); }

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 == 1 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

std::string scene_key(const json& scene) {
  return scene.at("suite").get<std::string>() + "/" + scene.at("name").get<std::string>();
}

// A scene's failure record (docs/bench.md, "A scene that fails"), or null: absent in files
// written before it existed.
const json& scene_failure(const json& scene) {
  static const json none = nullptr;
  return scene.contains("failure") ? scene.at("failure") : none;
}

std::size_t failed_scene_count(const json& bench) {
  const json& scenes = bench.at("scenes");
  return static_cast<std::size_t>(
      std::count_if(scenes.begin(), scenes.end(), [](const json& s) { return !scene_failure(s).is_null(); }));
}

// "FAILED in run pcf/3 (internal error): MESSAGE; 2 runs finished before it".
std::string failure_text(const json& scene) {
  const json& f = scene_failure(scene);
  const std::size_t runs = scene.at("runs").size();
  return fmt::format("FAILED{} ({} error): {}; {} run{} finished before it",
                     f.at("run").is_null() ? std::string(" before its runs") : " in run " + f.at("run").get<std::string>(),
                     f.at("kind").get<std::string>(), f.at("message").get<std::string>(), runs, runs == 1 ? "" : "s");
}

// ------------------------------------------------------------------ tables

struct Table {
  std::string title;
  std::string note;  // under the title
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  std::vector<bool> failed;  // per row: a robust run that failed
  std::size_t left_columns = 1;
};

// The runs summed over the scenes, in the matrix's order.
Table summary_table(const json& bench) {
  Table t;
  t.title = "Every run over the scenes";
  t.note = "Frame and build ms: medians over the scenes of each scene's median; hard errors: summed; soft error: the "
           "mean over the scenes with a soft reference; contour: the largest over the analytic scenes.";
  t.header = {"run", "scenes", "frame ms", "build ms", "hard errors", "scenes with hard errors", "failed",
              "soft mean error", "contour max"};
  for (const json& id_json : bench.at("methods")) {
    const std::string id = id_json.get<std::string>();
    std::vector<double> frame, build;
    double hard = 0.0, soft_sum = 0.0;
    std::size_t scenes = 0, with_hard = 0, failed = 0, soft_n = 0;
    std::optional<double> contour;
    for (const json& scene : bench.at("scenes"))
      for (const json& run : scene.at("runs")) {
        if (run.at("id") != id) continue;
        ++scenes;
        frame.push_back(frame_ms(run));
        build.push_back(number_at(run, {"time", "build_ms"}).value_or(0.0));
        const double h = number_at(run, {"error", "hard_errors"}).value_or(0.0);
        hard += h;
        with_hard += h > 0 ? 1 : 0;
        failed += run.at("failed").get<bool>() ? 1 : 0;
        if (const auto s = number_at(run, {"error", "soft", "mean_error"})) {
          soft_sum += *s;
          ++soft_n;
        }
        if (const auto c = number_at(run, {"error", "contour", "max"})) contour = std::max(contour.value_or(0.0), *c);
      }
    if (scenes == 0) continue;
    const bool edges = id.rfind("edges/", 0) == 0;  // no lit mask: no pixel figures
    t.rows.push_back({id, std::to_string(scenes), ms_text(median(frame)), ms_text(median(build)),
                      edges ? "-" : thousands(hard), edges ? "-" : std::to_string(with_hard), std::to_string(failed),
                      soft_n > 0 ? error_text(soft_sum / static_cast<double>(soft_n)) : "-", error_text(contour)});
    t.failed.push_back(failed > 0);
  }
  return t;
}

// The analytic scenes, grouped by their light (the name's suffix after the last '-'), each
// group's rows the shapes in the suite's order: one cell per silhouette run.
std::vector<Table> analytic_tables(const json& bench, bool contour) {
  std::vector<std::string> lights;
  std::map<std::string, std::vector<const json*>> by_light;
  for (const json& scene : bench.at("scenes")) {
    if (scene.at("suite") != "analytic" || !scene.at("skipped").is_null()) continue;
    const std::string name = scene.at("name");
    const std::size_t dash = name.rfind('-');
    const std::string light = dash == std::string::npos ? "" : name.substr(dash + 1);
    if (by_light.count(light) == 0) lights.push_back(light);
    by_light[light].push_back(&scene);
  }
  std::vector<Table> out;
  for (const std::string& light : lights) {
    std::vector<std::string> ids;
    for (const json* scene : by_light[light])
      for (const json& run : (*scene).at("runs"))
        if (run.at("family") == "silhouette" && std::find(ids.begin(), ids.end(), run.at("id")) == ids.end())
          ids.push_back(run.at("id"));
    if (ids.empty()) continue;
    Table t;
    const std::string light_text = light == "point" ? "point light at (1.2, 4, 0.8)"
                                   : light == "sun" ? "sun towards (0.3, 1, 0.2)"
                                                    : light;
    if (contour) {
      t.title = "Contour error on the floor, " + light_text;
      t.note = "Max / mean distance (world units) from each method's shadow boundary to the analytic conic, and "
               "(in parentheses) the run's CPU build ms (the volumes, the inputs, the upload).";
    } else {
      t.title = "Pixels against the analytic shadow, " + light_text;
      t.note = "Pixels disagreeing on the floor / on the caster itself (against the interpolated-normal terminator), "
               "and (in parentheses) the median frame ms.";
    }
    t.header = {"caster"};
    t.header.insert(t.header.end(), ids.begin(), ids.end());
    for (const json* scene : by_light[light]) {
      std::string name = (*scene).at("name");
      name = name.substr(0, name.rfind('-'));
      std::vector<std::string> row{name};
      for (const std::string& id : ids) {
        std::string cell = "-";
        for (const json& run : (*scene).at("runs")) {
          if (run.at("id") != id) continue;
          if (contour) {
            const auto max = number_at(run, {"error", "contour", "max"});
            const auto mean = number_at(run, {"error", "contour", "mean"});
            if (max && mean)
              cell = fmt::format("{:.4f} / {:.4f} ({})", *max, *mean, ms_text(number_at(run, {"time", "build_ms"})));
          } else {
            const auto floor = number_at(run, {"error", "analytic", "receiver_disagree"});
            const auto self = number_at(run, {"error", "analytic", "caster_disagree"});
            if (floor && self) cell = fmt::format("{} / {} ({})", thousands(*floor), thousands(*self), ms_text(frame_ms(run)));
          }
        }
        row.push_back(cell);
      }
      t.rows.push_back(row);
      t.failed.push_back(false);
    }
    out.push_back(std::move(t));
  }
  return out;
}

// The soft-shadow error of one scene: the runs compared with its soft reference, cpu (the exact
// hard shadow) and the shadow-map family.
std::optional<Table> soft_table(const json& scene) {
  if (scene.at("soft_reference").is_null()) return std::nullopt;
  Table t;
  t.title = "Soft-shadow error, " + scene_key(scene);
  t.note = fmt::format("Against the exact soft reference: a disk light of radius {:.4g}, {} samples ({:.1f} s). Mean "
                       "|error| of light over every compared pixel, in the umbra, the penumbra and outside it; signed "
                       "mean; leaks (contact pixels lit) and acne (lit pixels darkened); median frame ms.",
                       number_at(scene, {"soft_reference", "radius"}).value_or(0.0),
                       thousands(number_at(scene, {"soft_reference", "samples"}).value_or(0.0)),
                       number_at(scene, {"soft_reference", "seconds"}).value_or(0.0));
  t.header = {"run", "mean", "umbra", "penumbra", "outside", "signed", "leaks", "acne", "ms"};
  for (const json& run : scene.at("runs")) {
    if (run.at("family") != "shadowmap" && run.at("id") != "cpu") continue;
    if (run.at("error").at("soft").is_null()) continue;
    const json& s = run.at("error").at("soft");
    t.rows.push_back({run.at("id"), error_text(number_at(s, {"mean_error"})), error_text(number_at(s, {"umbra_mean_error"})),
                      error_text(number_at(s, {"penumbra_mean_error"})),
                      error_text(number_at(s, {"outside_penumbra_mean_error"})),
                      signed_text(number_at(s, {"mean_signed_error"})),
                      count_text(number_at(s, {"leaks"})) + " / " + count_text(number_at(s, {"contact"})),
                      count_text(number_at(s, {"acne"})), ms_text(frame_ms(run))});
    t.failed.push_back(false);
  }
  if (t.rows.empty()) return std::nullopt;
  return t;
}

// Every run of one scene.
Table scene_table(const json& scene) {
  Table t;
  t.title = scene_key(scene);
  const json& size = scene.at("size");
  t.note = fmt::format("`{}`: {} triangles, {} light(s), {}x{}; exact image {:.2f} s; scene {:.1f} s.",
                       scene.at("input").get<std::string>(), count_text(number_at(scene, {"triangles"})),
                       count_text(number_at(scene, {"lights"})), size.is_array() ? size.at(0).get<int>() : 0,
                       size.is_array() ? size.at(1).get<int>() : 0, number_at(scene, {"exact_seconds"}).value_or(0.0),
                       number_at(scene, {"seconds"}).value_or(0.0));
  if (!scene_failure(scene).is_null()) t.note = failure_text(scene) + ". " + t.note;
  t.header = {"run", "frame ms", "min", "max", "build ms", "hard errors", "ambiguous", "closed", "soft mean",
              "contour max", "analytic floor / caster"};
  for (const json& run : scene.at("runs")) {
    const json& e = run.at("error");
    const auto floor = number_at(e, {"analytic", "receiver_disagree"});
    const auto self = number_at(e, {"analytic", "caster_disagree"});
    t.rows.push_back({run.at("id").get<std::string>() + (run.at("robust").get<bool>() ? "" : " (baseline)"),
                      ms_text(frame_ms(run)), ms_text(number_at(run, {"time", "frame_ms", "min"})),
                      ms_text(number_at(run, {"time", "frame_ms", "max"})), ms_text(number_at(run, {"time", "build_ms"})),
                      count_text(number_at(e, {"hard_errors"})), count_text(number_at(e, {"ambiguous"})),
                      closed_text(run), error_text(number_at(e, {"soft", "mean_error"})),
                      error_text(number_at(e, {"contour", "max"})),
                      floor && self ? thousands(*floor) + " / " + thousands(*self) : "-"});
    t.failed.push_back(run.at("failed").get<bool>());
  }
  return t;
}

// The stage medians of every run of one scene (render --timing's table): the wall ms of each
// stage bounded by glFinish on a software renderer (cpu_ms), the timer queries on a GPU (gpu_ms).
Table stage_table(const json& scene, bool synchronised) {
  Table t;
  t.title = "Stages, " + scene_key(scene);
  t.note = synchronised ? "Median ms per stage (wall, each stage bounded by glFinish), and the frame by the wall clock "
                          "and by GL timestamps."
                        : "Median ms per stage (GL timer queries), and the frame by the wall clock and by GL timestamps.";
  const char* source = synchronised ? "cpu_ms" : "gpu_ms";
  // The stages some run of the scene has, in frame order (render's, then the edge maps').
  std::vector<const char*> stages;
  for (const char* stage : {"volume", "depth", "stencil", "shadow_map", "smoothie_map", "lit", "g_buffer", "edge_filter",
                            "composite"})
    if (std::any_of(scene.at("runs").begin(), scene.at("runs").end(),
                    [&](const json& run) { return number_at(run, {"time", "gpu_ms", stage, "median"}).has_value(); }))
      stages.push_back(stage);
  t.header = {"run"};
  t.header.insert(t.header.end(), stages.begin(), stages.end());
  t.header.push_back("frame (wall)");
  t.header.push_back("frame (GPU)");
  for (const json& run : scene.at("runs")) {
    std::vector<std::string> row{run.at("id")};
    for (const char* stage : stages) row.push_back(ms_text(number_at(run, {"time", source, stage, "median"})));
    row.push_back(ms_text(number_at(run, {"time", "cpu_ms", "frame", "median"})));
    row.push_back(ms_text(number_at(run, {"time", "gpu_ms", "frame", "median"})));
    t.rows.push_back(row);
    t.failed.push_back(false);
  }
  return t;
}

// The exact image against the ray tracer, scene by scene in order of triangles (docs/diff.md's
// scaling table, from the run's own scenes): the exact image's seconds beside each ray-traced
// run's BVH build plus one image's rays, and their ratio. None without a ray-traced run.
std::optional<Table> exact_vs_ray_traced_table(const json& bench) {
  const std::array<const char*, 2> ids{"rt-robust", "rt"};
  struct Row {
    double triangles;
    std::vector<std::string> cells;
  };
  std::vector<Row> rows;
  bool any = false;
  for (const json& scene : bench.at("scenes")) {
    // The exact image alone; files written before the key existed have only exact_seconds, which
    // includes the float-rounded twin (a second exact image).
    std::optional<double> exact = number_at(scene, {"exact_image_seconds"});
    if (!exact) exact = number_at(scene, {"exact_seconds"});
    if (!exact || !scene.at("skipped").is_null()) continue;
    const json& size = scene.at("size");
    Row row{number_at(scene, {"triangles"}).value_or(0.0),
            {scene_key(scene), count_text(number_at(scene, {"triangles"})),
             size.is_array() ? fmt::format("{}x{}", size.at(0).get<int>(), size.at(1).get<int>()) : "-",
             fmt::format("{:.3f}", *exact)}};
    bool has_run = false;
    for (const char* id : ids) {
      const auto run = std::find_if(scene.at("runs").begin(), scene.at("runs").end(),
                                    [&](const json& r) { return r.at("id") == id; });
      if (run == scene.at("runs").end()) {
        row.cells.insert(row.cells.end(), {"-", "-"});
        continue;
      }
      const double seconds = (number_at(*run, {"time", "build_ms"}).value_or(0.0) + frame_ms(*run)) / 1000.0;
      row.cells.push_back(fmt::format("{:.3f}", seconds));
      row.cells.push_back(seconds > 0.0 ? fmt::format("{:.1f}", *exact / seconds) : "-");
      has_run = true;
    }
    if (!has_run) continue;
    any = true;
    rows.push_back(std::move(row));
  }
  if (!any) return std::nullopt;
  std::stable_sort(rows.begin(), rows.end(), [](const Row& a, const Row& b) { return a.triangles < b.triangles; });
  Table t;
  t.title = "The exact image against Embree, by triangles";
  t.note = "Seconds on the TBB threads under `host` (--threads). Exact: the exact image once (`exact_image_seconds`: its "
           "tree, the centre and corner rays' hits, the footprints, every count exact; not its float-rounded twin). Embree (rt-robust, rt): its BVH build "
           "plus one image's rays (the centre rays and a shadow ray per hit and light), medians over the frames. "
           "Embree answers less per pixel, so the ratio is what certainty costs here; bench/exact_image_bench's "
           "ExactVsEmbree times both on the same rays, corners included (docs/diff.md#scaling-100k-1m-and-4m-triangles).";
  t.header = {"scene", "triangles", "image", "exact s", "rt-robust s", "exact / rt-robust", "rt s", "exact / rt"};
  for (Row& r : rows) {
    t.rows.push_back(std::move(r.cells));
    t.failed.push_back(false);
  }
  return t;
}

// Edge maps (issue 14): precision, recall and F1 of every edges run.
std::optional<Table> edges_table(const json& bench) {
  Table t;
  t.title = "Edge maps against the exact edges";
  t.note = "At each filter's default thresholds (profile: a depth step of 2% of the depth range; inner: creases above "
           "30 degrees), a detection matching a truth pixel within one pixel; profile and inner pixels pooled, then "
           "each class's F1.";
  t.header = {"scene", "run", "precision", "recall", "F1", "profile F1", "inner F1", "frame ms"};
  t.left_columns = 2;
  for (const json& scene : bench.at("scenes"))
    for (const json& run : scene.at("runs")) {
      if (run.at("error").at("edges").is_null()) continue;
      const json& e = run.at("error").at("edges");
      t.rows.push_back({scene_key(scene), run.at("id"), error_text(number_at(e, {"precision"})),
                        error_text(number_at(e, {"recall"})), error_text(number_at(e, {"f1"})),
                        error_text(number_at(e, {"profile", "f1"})), error_text(number_at(e, {"inner", "f1"})),
                        ms_text(frame_ms(run))});
      t.failed.push_back(false);
    }
  if (t.rows.empty()) return std::nullopt;
  return t;
}

// The scenes that threw: where and why (the bench went on without them).
std::optional<Table> failures_table(const json& bench) {
  Table t;
  t.title = "Scenes that failed";
  t.note = "A scene or run that threw: recorded, and the bench went on; the scene's finished runs are in its table.";
  t.header = {"scene", "run", "kind", "message"};
  t.left_columns = 4;  // text
  for (const json& scene : bench.at("scenes")) {
    const json& f = scene_failure(scene);
    if (f.is_null()) continue;
    t.rows.push_back({scene_key(scene), f.at("run").is_null() ? "-" : f.at("run").get<std::string>(),
                      f.at("kind").get<std::string>(), f.at("message").get<std::string>()});
    t.failed.push_back(true);
  }
  if (t.rows.empty()) return std::nullopt;
  return t;
}

std::vector<std::pair<std::string, std::string>> facts(const json& bench) {
  const json& env = bench.at("environment");
  const auto text = [](const json& v) { return v.is_null() ? std::string("unknown") : v.is_string() ? v.get<std::string>() : v.dump(); };
  std::string commit = text(env.at("git_commit"));
  if (env.at("git_dirty").is_boolean() && env.at("git_dirty").get<bool>()) commit += " (with uncommitted changes)";
  const json& totals = bench.at("totals");
  return {{"command", bench.at("command").get<std::string>()},
          {"suite", fmt::format("{} ({} of {} scenes{})", bench.at("suite").get<std::string>(),
                                totals.at("scenes").get<std::size_t>(), bench.at("scene_count").get<std::size_t>(),
                                bench.at("shard").at("count").get<std::size_t>() > 1
                                    ? fmt::format(", shard {}/{}", bench.at("shard").at("index").get<std::size_t>(),
                                                  bench.at("shard").at("count").get<std::size_t>())
                                    : std::string())},
          {"runs", fmt::format("{} ({} failed), {} skipped scenes{}", totals.at("runs").get<std::size_t>(),
                               totals.at("failed_runs").get<std::size_t>(), totals.at("skipped_scenes").get<std::size_t>(),
                               failed_scene_count(bench) > 0 ? fmt::format(", {} FAILED scenes", failed_scene_count(bench))
                                                        : std::string())},
          {"complete", bench.value("complete", true)
                           ? std::string("yes")
                           : fmt::format("NO: the run was interrupted after {} scenes (bench.json is written after "
                                         "every scene)",
                                         totals.at("scenes").get<std::size_t>())},
          {"size", fmt::format("{}x{}", bench.at("size").at(0).get<int>(), bench.at("size").at(1).get<int>())},
          {"frames", fmt::format("{} timed after {} warm-up, stages {}", bench.at("frames").get<std::size_t>(),
                                 bench.at("warm_up_frames").get<std::size_t>(),
                                 text(env.at("stage_sync")) == "finish"
                                     ? "bounded by glFinish (software renderer: wall ms)"
                                     : "from GL timer queries")},
          {"renderer", text(env.at("renderer")) + ", GL " + text(env.at("gl_version"))},
          {"device", text(env.at("device"))},
          {"build", text(env.at("build_type")) + ", " + text(env.at("version"))},
          {"commit", commit},
          {"date", text(env.at("date"))},
          {"host", fmt::format("{} CPUs{}", number_at(env, {"host", "cpus"}).value_or(0.0),
                               number_at(env, {"host", "threads"})
                                   ? fmt::format(", {} TBB threads", *number_at(env, {"host", "threads"}))
                                   : std::string())},
          {"seconds", fmt::format("{:.1f} s", number_at(bench, {"seconds"}).value_or(0.0))}};
}

// ------------------------------------------------------------------ markdown

std::string markdown_cell(const std::string& text) {
  std::string out;
  for (char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

std::string markdown_table(const Table& t, const std::string& heading) {
  std::string md = heading + " " + t.title + "\n\n";
  if (!t.note.empty()) md += t.note + "\n\n";
  md += "|";
  for (const std::string& h : t.header) md += " " + markdown_cell(h) + " |";
  md += "\n|";
  for (std::size_t c = 0; c < t.header.size(); ++c) md += c < t.left_columns ? " --- |" : " ---: |";
  md += "\n";
  for (std::size_t r = 0; r < t.rows.size(); ++r) {
    md += "|";
    for (std::size_t c = 0; c < t.rows[r].size(); ++c) {
      const std::string cell = markdown_cell(t.rows[r][c]);
      md += " " + (c == 0 && t.failed[r] ? "**" + cell + " FAILED**" : cell) + " |";
    }
    md += "\n";
  }
  return md + "\n";
}

// ------------------------------------------------------------------ HTML

constexpr std::string_view kBenchReportStyle = R"(
body { font-family: sans-serif; margin: 1.5em; color: #222; max-width: 110em; }
table { border-collapse: collapse; margin: 0.5em 0 1.5em; font-size: 0.9em; }
th, td { border: 1px solid #bbb; padding: 0.2em 0.6em; text-align: right; }
th.left, td.left { text-align: left; }
tr.fail td { background: #fdd; }
.figures { display: flex; flex-wrap: wrap; gap: 1em; }
figure { margin: 0; }
figure img { max-width: 320px; image-rendering: pixelated; border: 1px solid #ccc; background: #444; }
figure.plot img { max-width: 720px; image-rendering: auto; background: #fff; }
figcaption { font-size: 0.8em; max-width: 320px; }
figure.plot figcaption { max-width: 720px; }
.legend { font-size: 0.85em; margin: 0.3em 0; }
.legend span.swatch { display: inline-block; width: 1.4em; height: 1em; vertical-align: middle; border: 1px solid #888; }
.legend span.label { margin: 0 0.6em 0 0.2em; }
details { margin: 0.4em 0; }
summary { cursor: pointer; font-weight: bold; }
p.note { font-size: 0.85em; color: #555; max-width: 60em; }
p.missing { color: #a00; }
)";

std::string html_table(const Table& t, const std::string& heading_tag) {
  std::string html = fmt::format("<{0}>{1}</{0}>\n", heading_tag, html_escape(t.title));
  if (!t.note.empty()) html += "<p class=\"note\">" + html_escape(t.note) + "</p>\n";
  html += "<table>\n<tr>";
  for (std::size_t c = 0; c < t.header.size(); ++c)
    html += fmt::format("<th{}>{}</th>", c < t.left_columns ? " class=\"left\"" : "", html_escape(t.header[c]));
  html += "</tr>\n";
  for (std::size_t r = 0; r < t.rows.size(); ++r) {
    html += t.failed[r] ? "<tr class=\"fail\">" : "<tr>";
    for (std::size_t c = 0; c < t.rows[r].size(); ++c)
      html += fmt::format("<td{}>{}</td>", c < t.left_columns ? " class=\"left\"" : "", html_escape(t.rows[r][c]));
    html += "</tr>\n";
  }
  return html + "</table>\n";
}

std::optional<std::vector<std::uint8_t>> read_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return std::nullopt;
  return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::string image_figure(const fs::path& dir, const std::string& relative, const std::string& caption,
                         const std::string& figure_class = "") {
  const std::optional<std::vector<std::uint8_t>> png = read_bytes(dir / relative);
  if (!png || png->empty())
    return fmt::format("<p class=\"missing\">{}: {} is missing</p>\n", html_escape(caption), html_escape(relative));
  return fmt::format("<figure{2}><img alt=\"{0}\" src=\"data:image/png;base64,{1}\"><figcaption>{0}</figcaption></figure>\n",
                     html_escape(caption), base64(*png),
                     figure_class.empty() ? std::string() : " class=\"" + figure_class + "\"");
}

// The legend of the counts picture (pipeline/comparison_pictures.h's count_colour_image), as
// diff's report draws it (cli/diff_report.h).
std::string counts_legend_html(std::uint32_t scale) {
  std::string html = "<div class=\"legend\">exact counts n(P), viridis: ";
  for (const LegendSwatch& s : counts_legend(scale))
    html += fmt::format("<span class=\"swatch\" style=\"background:rgb({},{},{})\"></span><span class=\"label\">{}</span>",
                        s.colour[0], s.colour[1], s.colour[2], html_escape(s.label));
  return html + " (no hit: transparent)</div>\n";
}

std::string plots_html(const fs::path& dir, const std::string& plots_note) {
  std::string html = "<h2>Plots</h2>\n";
  if (!plots_note.empty()) return html + "<p class=\"note\">" + html_escape(plots_note) + "</p>\n";
  std::ifstream in(dir / "plots/index.json");
  json index;
  try {
    index = json::parse(in);
  } catch (const json::exception&) {
    return html + "<p class=\"missing\">plots/index.json is missing or not JSON</p>\n";
  }
  html += "<div class=\"figures\">\n";
  for (const json& plot : index)
    html += image_figure(dir, "plots/" + plot.value("file", std::string()),
                         plot.value("title", std::string()) + ": " + plot.value("caption", std::string()), "plot");
  return html + "</div>\n";
}

std::string scene_html(const json& scene, const fs::path& dir, bool synchronised) {
  const bool failed = !scene_failure(scene).is_null();
  std::string html =
      fmt::format("<details><summary>{}{}</summary>\n", html_escape(scene_key(scene)), failed ? " (FAILED)" : "");
  if (!scene.at("skipped").is_null()) return html + "<p>skipped: " + html_escape(scene.at("skipped").get<std::string>()) + "</p>\n</details>\n";
  if (failed && scene.at("runs").empty())
    return html + "<p class=\"missing\">" + html_escape(failure_text(scene)) + "</p>\n</details>\n";
  html += html_table(scene_table(scene), "h4");
  html += html_table(stage_table(scene, synchronised), "h4");
  if (const std::optional<Table> soft = soft_table(scene)) html += html_table(*soft, "h4");
  const json& images = scene.at("images");
  if (!images.empty()) {
    html += "<div class=\"figures\">\n";
    if (images.contains("exact_mask")) html += image_figure(dir, images.at("exact_mask"), "exact lit mask (first light)");
    if (images.contains("exact_counts"))
      html += image_figure(dir, images.at("exact_counts"), "exact counts n(P) (first light; legend below)");
    if (images.contains("exact_ambiguous"))
      html += image_figure(dir, images.at("exact_ambiguous"), "exact image: ambiguous pixels (white)");
    html += "</div>\n" + counts_legend_html(static_cast<std::uint32_t>(number_at(scene, {"count_scale"}).value_or(1.0)));
  }
  html += "<p class=\"legend\">Overlays: <span class=\"swatch\" style=\"background:#f00\"></span><span class=\"label\">"
          "hard error</span><span class=\"swatch\" style=\"background:#ff0\"></span><span class=\"label\">ambiguous "
          "pixel</span> over the rendered frame (first light). Soft error: method minus reference, blue too dark, red "
          "too bright, green where coverage differs.</p>\n<div class=\"figures\">\n";
  for (const json& run : scene.at("runs")) {
    const json& run_images = run.at("error").at("images");
    if (run_images.contains("overlay"))
      html += image_figure(dir, run_images.at("overlay"),
                           fmt::format("{}: {} hard errors", run.at("id").get<std::string>(),
                                       count_text(number_at(run, {"error", "hard_errors"}))));
    if (run_images.contains("soft_error"))
      html += image_figure(dir, run_images.at("soft_error"),
                           fmt::format("{}: soft error, mean {}", run.at("id").get<std::string>(),
                                       error_text(number_at(run, {"error", "soft", "mean_error"}))));
  }
  return html + "</div>\n</details>\n";
}

}  // namespace

std::string bench_csv(const json& bench) {
  static const std::vector<std::string> kColumns{
      "suite", "scene", "input", "width", "height", "triangles", "lights", "run", "method", "family", "sign",
      "shadow_map_size", "pcf_kernel", "light_radius", "epsilon", "smoothie_width", "robust", "failed",
      "frame_ms_median", "frame_ms_min", "frame_ms_max", "build_ms", "hard_errors", "ambiguous", "agree", "closed",
      "volume_triangles", "soft_mean_error", "soft_max_error", "soft_umbra_error", "soft_penumbra_error",
      "soft_outside_error", "soft_signed_error", "soft_leaks", "soft_contact", "soft_acne", "soft_lit_facing",
      "analytic_receiver_disagree", "analytic_caster_disagree", "contour_max", "contour_mean", "edges_precision",
      "edges_recall", "edges_f1"};
  const auto field = [](const std::string& text) {
    if (text.find_first_of(",\"\n") == std::string::npos) return text;
    std::string out = "\"";
    for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
  };
  const auto value = [](const json& j) -> std::string {
    if (j.is_null()) return "";
    if (j.is_string()) return j.get<std::string>();
    if (j.is_boolean()) return j.get<bool>() ? "true" : "false";
    if (j.is_number_integer() || j.is_number_unsigned()) return j.dump();
    if (j.is_number()) return fmt::format("{:.6g}", j.get<double>());
    return j.dump();
  };
  const auto at = [](const json& j, std::initializer_list<const char*> path) -> json {
    const json* p = &j;
    for (const char* key : path) {
      if (!p->is_object() || !p->contains(key)) return nullptr;
      p = &(*p)[key];
    }
    return *p;
  };
  std::string csv;
  for (std::size_t c = 0; c < kColumns.size(); ++c) {
    if (c > 0) csv += ',';
    csv += kColumns[c];
  }
  csv += "\n";
  for (const json& scene : bench.at("scenes"))
    for (const json& run : scene.at("runs")) {
      const json& e = run.at("error");
      const json& p = run.at("parameter");
      const std::vector<json> row{scene.at("suite"), scene.at("name"), scene.at("input"), at(scene, {"size"}).is_array() ? scene.at("size").at(0) : json(),
                                  at(scene, {"size"}).is_array() ? scene.at("size").at(1) : json(), scene.at("triangles"),
                                  scene.at("lights"), run.at("id"), run.at("method"), run.at("family"), at(p, {"sign"}),
                                  at(p, {"shadow_map_size"}), at(p, {"pcf_kernel"}), at(p, {"light_radius"}),
                                  at(p, {"epsilon"}), at(p, {"smoothie_width"}), run.at("robust"), run.at("failed"),
                                  at(run, {"time", "frame_ms", "median"}), at(run, {"time", "frame_ms", "min"}),
                                  at(run, {"time", "frame_ms", "max"}), at(run, {"time", "build_ms"}), e.at("hard_errors"),
                                  e.at("ambiguous"), e.at("agree"), e.at("closed"), e.at("volume_triangles"),
                                  at(e, {"soft", "mean_error"}), at(e, {"soft", "max_error"}),
                                  at(e, {"soft", "umbra_mean_error"}), at(e, {"soft", "penumbra_mean_error"}),
                                  at(e, {"soft", "outside_penumbra_mean_error"}), at(e, {"soft", "mean_signed_error"}),
                                  at(e, {"soft", "leaks"}), at(e, {"soft", "contact"}), at(e, {"soft", "acne"}),
                                  at(e, {"soft", "lit_facing"}), at(e, {"analytic", "receiver_disagree"}),
                                  at(e, {"analytic", "caster_disagree"}), at(e, {"contour", "max"}),
                                  at(e, {"contour", "mean"}), at(e, {"edges", "precision"}), at(e, {"edges", "recall"}),
                                  at(e, {"edges", "f1"})};
      for (std::size_t c = 0; c < row.size(); ++c) {
        if (c > 0) csv += ',';
        csv += field(value(row[c]));
      }
      csv += "\n";
    }
  return csv;
}

std::string bench_markdown(const json& bench) {
  std::string md = "# shadowcert bench\n\n";
  for (const auto& [what, value] : facts(bench)) md += fmt::format("- {}: {}\n", what, what == "command" ? "`" + value + "`" : value);
  md += "\nTimes in ms: `frame ms` is the median over the timed frames (the wall clock with every stage bounded by "
        "`glFinish` on a software renderer, GL timestamps on a GPU), summed over the lights; `build ms` the CPU work "
        "before the frames (inputs, volumes, upload). Errors: pixels against the exact image (hard errors, ambiguous), "
        "closure, soft-shadow error against the exact soft reference, contour error against the analytic conic, "
        "pixels against the analytic shadow (docs/bench.md).\n\n";
  if (const std::optional<Table> t = failures_table(bench)) md += markdown_table(*t, "##");
  md += markdown_table(summary_table(bench), "##");
  if (const std::optional<Table> t = exact_vs_ray_traced_table(bench)) md += markdown_table(*t, "##");
  for (const Table& t : analytic_tables(bench, true)) md += markdown_table(t, "##");
  for (const Table& t : analytic_tables(bench, false)) md += markdown_table(t, "##");
  for (const json& scene : bench.at("scenes"))
    if (const std::optional<Table> t = soft_table(scene)) md += markdown_table(*t, "##");
  if (const std::optional<Table> t = edges_table(bench)) md += markdown_table(*t, "##");
  md += "## Every run, per scene\n\n";
  const bool synchronised = bench.at("environment").value("stage_sync", std::string()) == "finish";
  for (const json& scene : bench.at("scenes")) {
    if (!scene.at("skipped").is_null()) {
      md += fmt::format("### {}\n\nskipped: {}\n\n", scene_key(scene), scene.at("skipped").get<std::string>());
      continue;
    }
    if (!scene_failure(scene).is_null() && scene.at("runs").empty()) {  // else its table's note says it
      md += fmt::format("### {}\n\n{}\n\n", scene_key(scene), failure_text(scene));
      continue;
    }
    md += markdown_table(scene_table(scene), "###");
    md += markdown_table(stage_table(scene, synchronised), "####");
  }
  return md;
}

std::string bench_report_html(const json& bench, const fs::path& dir, const std::string& plots_note) {
  std::string html = fmt::format("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
                                 "<title>shadowcert bench: {0}</title>\n<style>{1}</style>\n</head>\n<body>\n"
                                 "<h1>shadowcert bench: {0}</h1>\n<ul>\n",
                                 html_escape(bench.at("suite").get<std::string>()), kBenchReportStyle);
  for (const auto& [what, value] : facts(bench))
    html += fmt::format("<li>{}: {}</li>\n", html_escape(what), html_escape(value));
  html += "</ul>\n";
  html += plots_html(dir, plots_note);
  if (const std::optional<Table> t = failures_table(bench)) html += html_table(*t, "h2");
  html += html_table(summary_table(bench), "h2");
  if (const std::optional<Table> t = exact_vs_ray_traced_table(bench)) html += html_table(*t, "h2");
  for (const Table& t : analytic_tables(bench, true)) html += html_table(t, "h2");
  for (const Table& t : analytic_tables(bench, false)) html += html_table(t, "h2");
  if (const std::optional<Table> t = edges_table(bench)) html += html_table(*t, "h2");
  html += "<h2>Scenes</h2>\n<p class=\"note\">Each scene's runs, its soft-shadow error, its exact pictures and every "
          "run's overlay (click to open).</p>\n";
  const bool synchronised = bench.at("environment").value("stage_sync", std::string()) == "finish";
  for (const json& scene : bench.at("scenes")) html += scene_html(scene, dir, synchronised);
  return html + "</body>\n</html>\n";
}

}  // namespace shadowcert::cli
