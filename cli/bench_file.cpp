#include "cli/bench_file.h"

#include <fmt/core.h>

#include <limits>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "core/input_error.h"
#include "scene/json_field.h"

namespace shadowcert::cli {
namespace {

using nlohmann::json;

// ---- reading with the key path (scene/json_field.h; every failure names the file and the path)

// Member `name` of object `o`, which must be there ("PATH: no key 'name'").
JsonField bench_key(const JsonField& o, std::string_view name) {
  if (std::optional<JsonField> m = o.member(name)) return *m;
  o.fail("no key '" + std::string(name) + "'");
}

// nullopt for null, else the value.
std::optional<JsonField> bench_unless_null(const JsonField& f) {
  if (f.json().is_null()) return std::nullopt;
  return f;
}

std::vector<JsonField> bench_elements(const JsonField& f) {
  std::vector<JsonField> out;
  const std::size_t n = f.array_size();
  out.reserve(n);
  for (std::size_t i = 0; i < n; ++i) out.push_back(f.element(i));
  return out;
}

std::uint64_t bench_count(const JsonField& f) { return f.unsigned_integer(std::numeric_limits<std::uint64_t>::max()); }

// Fails unless `f` is an object.
const JsonField& bench_object(const JsonField& f) {
  (void)f.member("");  // member() requires an object
  return f;
}

// ---- the parts of the schema (docs/bench.md#benchjson)

void check_string_or_null(const JsonField& f) {
  if (const std::optional<JsonField> v = bench_unless_null(f)) (void)v->string();
}

void check_number_or_null(const JsonField& f) {
  if (const std::optional<JsonField> v = bench_unless_null(f)) (void)v->number();
}

void check_count_or_null(const JsonField& f) {
  if (const std::optional<JsonField> v = bench_unless_null(f)) (void)bench_count(*v);
}

// A key the readers take only where it is there (bench_outputs.cpp's number_at): absent, null or
// a number.
void check_optional_number(const JsonField& object, std::string_view key) {
  if (const std::optional<JsonField> f = object.member(key)) check_number_or_null(*f);
}

void check_boolean_or_null(const JsonField& f) {
  if (const std::optional<JsonField> v = bench_unless_null(f)) (void)v->boolean();
}

// [w, h], as "size" is.
void check_image_size(const JsonField& f) {
  const std::vector<JsonField> wh = bench_elements(f);
  if (wh.size() != 2) f.fail(fmt::format("expected [width, height], got {}", f.json().dump()));
  for (const JsonField& e : wh) (void)bench_count(e);
}

// {"name": "PATH", ...}: images under the output folder.
void check_image_paths(const JsonField& f) {
  bench_object(f);
  for (const auto& item : f.json().items()) (void)bench_key(f, item.key()).string();
}

void check_environment(const JsonField& env) {
  // The outputs show these as text ("unknown" for null): there, a string or null.
  for (const char* key : {"renderer", "gl_version", "device", "build_type", "git_commit", "date", "version"})
    check_string_or_null(bench_key(env, key));
  for (const char* key : {"software_renderer", "git_dirty"}) check_boolean_or_null(bench_key(env, key));
  (void)bench_key(env, "stage_sync").string();  // picks the stage table's column
  if (const std::optional<JsonField> host = env.member("host")) bench_object(*host);
}

void check_run_time(const JsonField& time) {
  const JsonField frame = bench_key(time, "frame_ms");
  for (const char* key : {"median", "min", "max"}) (void)bench_key(frame, key).number();
  bench_object(bench_key(time, "gpu_ms"));
  bench_object(bench_key(time, "cpu_ms"));
  (void)bench_key(time, "build_ms").number();
}

void check_run_error(const JsonField& error) {
  // Null for an edges run (no lit mask).
  for (const char* key : {"hard_errors", "ambiguous", "agree", "coverage_errors", "lit_errors", "count_errors"})
    check_count_or_null(bench_key(error, key));
  check_boolean_or_null(bench_key(error, "closed"));
  check_count_or_null(bench_key(error, "volume_triangles"));
  check_string_or_null(bench_key(error, "capacity_error"));
  // Where the plots read a figure unguarded it must be there; the tables read the others only
  // where they are.
  if (const std::optional<JsonField> soft = bench_unless_null(bench_key(error, "soft"))) {
    (void)bench_key(*soft, "mean_error").number();
    for (const char* key : {"max_error", "mean_signed_error", "umbra_mean_error", "penumbra_mean_error",
                            "outside_penumbra_mean_error", "leaks", "contact", "acne", "lit_facing"})
      check_optional_number(*soft, key);
  }
  if (const std::optional<JsonField> analytic = bench_unless_null(bench_key(error, "analytic")))
    for (const char* key : {"receiver_disagree", "caster_disagree"}) check_optional_number(*analytic, key);
  if (const std::optional<JsonField> contour = bench_unless_null(bench_key(error, "contour"))) {
    (void)bench_key(*contour, "max").number();
    check_optional_number(*contour, "mean");
  }
  if (const std::optional<JsonField> edges = bench_unless_null(bench_key(error, "edges"))) {
    for (const char* key : {"precision", "recall"}) (void)bench_key(*edges, key).number();
    check_optional_number(*edges, "f1");
  }
  check_image_paths(bench_key(error, "images"));
}

void check_run(const JsonField& run, const std::set<std::string>& methods) {
  const JsonField id = bench_key(run, "id");
  if (methods.count(id.string()) == 0) id.fail("run \"" + id.string() + "\" is not one of the top level's 'methods'");
  const std::string method = bench_key(run, "method").string();
  (void)bench_key(run, "family").string();
  const JsonField parameter = bench_object(bench_key(run, "parameter"));
  if (method == "smooth" || method == "smooth-gpu") (void)bench_key(parameter, "epsilon").number();  // a plot's axis
  (void)bench_key(run, "robust").boolean();
  (void)bench_key(run, "failed").boolean();
  check_run_time(bench_object(bench_key(run, "time")));
  check_run_error(bench_object(bench_key(run, "error")));
}

// A scene's "failure": absent or null, or what threw (docs/bench.md, "A scene that fails").
bool check_failure(const JsonField& scene) {
  const std::optional<JsonField> field = scene.member("failure");
  if (!field) return false;
  const std::optional<JsonField> f = bench_unless_null(*field);
  if (!f) return false;
  check_string_or_null(bench_key(*f, "run"));
  (void)bench_key(*f, "kind").string();
  (void)bench_key(*f, "message").string();
  return true;
}

struct BenchFileTally {
  std::uint64_t skipped = 0, runs = 0, failed_runs = 0, failed_scenes = 0;
};

void check_scene(const JsonField& scene, const std::set<std::string>& methods, BenchFileTally& tally) {
  for (const char* key : {"suite", "name", "input"}) (void)bench_key(scene, key).string();
  const JsonField skipped = bench_key(scene, "skipped");
  check_string_or_null(skipped);
  tally.skipped += skipped.json().is_null() ? 0 : 1;
  tally.failed_scenes += check_failure(scene) ? 1 : 0;
  const std::vector<JsonField> runs = bench_elements(bench_key(scene, "runs"));
  // A scene that ran has its figures; a skipped one, or one that failed before them, null.
  for (const char* key : {"triangles", "lights", "size"}) {
    const JsonField f = bench_key(scene, key);
    if (!runs.empty() && f.json().is_null()) f.fail("null, but the scene has runs");
  }
  check_count_or_null(bench_key(scene, "triangles"));
  check_count_or_null(bench_key(scene, "lights"));
  if (const std::optional<JsonField> size = bench_unless_null(bench_key(scene, "size"))) check_image_size(*size);
  check_number_or_null(bench_key(scene, "exact_seconds"));
  if (const std::optional<JsonField> soft = bench_unless_null(bench_key(scene, "soft_reference")))
    for (const char* key : {"radius", "angle_degrees", "samples", "seconds"}) check_optional_number(*soft, key);
  if (const std::optional<JsonField> analytic = bench_unless_null(bench_key(scene, "analytic"))) {
    bench_object(*analytic);
    check_optional_number(*analytic, "seconds");
  }
  check_number_or_null(bench_key(scene, "edge_truth_seconds"));
  if (const std::optional<JsonField> scale = scene.member("count_scale")) (void)bench_count(*scale);
  (void)bench_key(scene, "seconds").number();
  check_image_paths(bench_key(scene, "images"));
  for (const JsonField& run : runs) {
    check_run(bench_object(run), methods);
    ++tally.runs;
    tally.failed_runs += bench_key(run, "failed").boolean() ? 1 : 0;
  }
}

}  // namespace

BenchFileStatus check_bench_file(const json& bench, const std::string& file) {
  const JsonField root(bench, file);
  bench_object(root);
  const JsonField schema = bench_key(root, "schema");
  if (!schema.json().is_string() || schema.string() != kBenchSchema)
    schema.fail(fmt::format("{}: not a bench.json ({})", schema.json().dump(), kBenchSchema));
  (void)bench_key(root, "command").string();
  (void)bench_key(root, "suite").string();
  const JsonField shard = bench_key(root, "shard");
  const std::uint64_t k = bench_count(bench_key(shard, "index"));
  const std::uint64_t n = bench_count(bench_key(shard, "count"));
  if (n == 0 || k == 0 || k > n) shard.fail(fmt::format("expected 1 <= index <= count, got {}", shard.json().dump()));
  const std::uint64_t scene_count = bench_count(bench_key(root, "scene_count"));
  check_image_size(bench_key(root, "size"));
  (void)bench_count(bench_key(root, "warm_up_frames"));
  (void)bench_count(bench_key(root, "frames"));
  std::set<std::string> methods;
  for (const JsonField& m : bench_elements(bench_key(root, "methods"))) methods.insert(m.string());
  check_environment(bench_object(bench_key(root, "environment")));
  (void)bench_key(root, "seconds").number();
  BenchFileStatus status;
  if (const std::optional<JsonField> complete = root.member("complete")) status.complete = complete->boolean();
  status.shard_scenes = shard_scene_count(scene_count, k, n);

  // The shard's scenes by increasing index, none left out: all of them in a complete file, the
  // first ones in the file of an interrupted run.
  BenchFileTally tally;
  const std::vector<JsonField> scenes = bench_elements(bench_key(root, "scenes"));
  for (std::size_t j = 0; j < scenes.size(); ++j) {
    const JsonField index_field = bench_key(bench_object(scenes[j]), "index");
    const std::uint64_t index = bench_count(index_field);
    const std::uint64_t expected = (k - 1) + j * n;
    if (index >= scene_count) index_field.fail(fmt::format("scene index {} is beyond scene_count {}", index, scene_count));
    if (index % n != k - 1)
      index_field.fail(
          fmt::format("scene index {} is not in shard {}/{} (index % {} == {})", index, k, n, n, k - 1));
    if (index < expected)
      index_field.fail(fmt::format("scene index {} again, or out of order (the scenes go by increasing index)", index));
    if (index > expected)
      throw InputError(file, fmt::format("scene index {} of shard {}/{} is missing: {} comes after {} (an unfinished "
                                         "run?)",
                                         expected, k, n, index, j == 0 ? std::string("none") : std::to_string(expected - n)));
    check_scene(scenes[j], methods, tally);
  }
  status.scenes = scenes.size();
  if (status.complete && status.scenes < status.shard_scenes)
    throw InputError(file, fmt::format("scene index {} of shard {}/{} is missing: 'scenes' holds {} of the shard's {}, "
                                       "but the file says it is complete (an unfinished run?)",
                                       (k - 1) + status.scenes * n, k, n, status.scenes, status.shard_scenes));

  // The totals are the scenes' (bench.md's headline shows them).
  const JsonField totals = bench_object(bench_key(root, "totals"));
  const auto total = [&](const char* key, std::uint64_t expected) {
    const JsonField f = bench_key(totals, key);
    if (const std::uint64_t value = bench_count(f); value != expected)
      f.fail(fmt::format("{}, but the scenes add up to {}", value, expected));
  };
  total("scenes", scenes.size());
  total("skipped_scenes", tally.skipped);
  total("runs", tally.runs);
  total("failed_runs", tally.failed_runs);
  if (totals.member("failed_scenes") || tally.failed_scenes > 0) total("failed_scenes", tally.failed_scenes);
  return status;
}

}  // namespace shadowcert::cli
