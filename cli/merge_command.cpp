#include "cli/merge_command.h"

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <tuple>
#include <vector>

#include "campaign/case_shard.h"
#include "cli/bench_file.h"
#include "cli/exit_code.h"
#include "core/input_error.h"
#include "io/output_file.h"
#include "scene/json_text.h"

namespace shadowcert::cli {
namespace {

using nlohmann::json;

constexpr const char* kFuzzSchema = "shadowcert-fuzz/1";

struct MergeOptions {
  std::vector<std::string> files;
  std::string json_file;
};

// One input file: the name as given, its JSON, and the shard it says it is.
struct Part {
  std::string file;
  json value;
  std::uint64_t index = 1;  // K of K/N
  std::uint64_t count = 1;  // N
};

json read_json_object(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file, "cannot open");
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  json value = parse_json_text(text, file);  // syntax errors with their line, duplicate keys
  if (!value.is_object()) throw InputError(file, "not a JSON object: not a fuzz --json or bench.json file");
  return value;
}

// object[key], which must be there: `where` names the object in the message ("" at the top).
const json& need(const Part& part, const json& object, const std::string& key, const std::string& where = "") {
  if (!object.is_object() || !object.contains(key))
    throw InputError(part.file, fmt::format("no key '{}{}'", where, key));
  return object[key];
}

std::uint64_t need_count(const Part& part, const json& object, const std::string& key, const std::string& where = "") {
  const json& value = need(part, object, key, where);
  if (!value.is_number_unsigned())
    throw InputError(part.file, fmt::format("'{}{}' must be a count (an integer >= 0), got {}", where, key, value.dump()));
  return value.get<std::uint64_t>();
}

double need_seconds(const Part& part, const json& object, const std::string& key, const std::string& where = "") {
  const json& value = need(part, object, key, where);
  if (!value.is_number()) throw InputError(part.file, fmt::format("'{}{}' must be a number, got {}", where, key, value.dump()));
  return value.get<double>();
}

std::vector<std::string> need_names(const Part& part, const json& object, const std::string& key,
                                    const std::string& where = "") {
  const json& value = need(part, object, key, where);
  std::vector<std::string> names;
  if (value.is_array())
    for (const json& name : value)
      if (name.is_string()) names.push_back(name.get<std::string>());
  if (!value.is_array() || names.size() != value.size())
    throw InputError(part.file, fmt::format("'{}{}' must be an array of names, got {}", where, key, value.dump()));
  return names;
}

// The file's shard {"index": K, "count": N}, 1 <= K <= N.
void read_shard(Part& part) {
  const json& shard = need(part, part.value, "shard");
  part.index = need_count(part, shard, "index", "shard.");
  part.count = need_count(part, shard, "count", "shard.");
  if (part.count == 0 || part.index == 0 || part.index > part.count)
    throw InputError(part.file, fmt::format("'shard' must have 1 <= index <= count, got {}", shard.dump()));
}

// Every file one shard of the same split, shards 1..N each once; then in shard order.
void check_shards(std::vector<Part>& parts) {
  const std::uint64_t n = parts.front().count;
  std::map<std::uint64_t, const Part*> seen;
  for (const Part& p : parts) {
    if (p.count != n)
      throw InputError(p.file, fmt::format("shard {}/{}, but {} is shard {}/{}: not shards of one split", p.index, p.count,
                                           parts.front().file, parts.front().index, n));
    const auto [at, fresh] = seen.emplace(p.index, &p);
    if (!fresh)
      throw InputError(p.file, fmt::format("shard {}/{} again: {} holds it too (overlapping shards)", p.index, n,
                                           at->second->file));
  }
  if (seen.size() != n) {
    std::string missing, given;
    for (std::uint64_t k = 1; k <= n; ++k)
      if (!seen.contains(k)) missing += fmt::format("{}{}/{}", missing.empty() ? "" : ", ", k, n);
    for (const Part& p : parts) given += fmt::format("{}{} ({}/{})", given.empty() ? "" : ", ", p.file, p.index, n);
    throw CLI::ValidationError("FILES", fmt::format("missing shard {}: given {}", missing, given));
  }
  std::sort(parts.begin(), parts.end(), [](const Part& a, const Part& b) { return a.index < b.index; });
}

// The value of `key` must be the same in every file (the same run, split).
void require_same(const std::vector<Part>& parts, const std::string& key) {
  const Part& first = parts.front();
  const json& expected = need(first, first.value, key);
  for (const Part& p : parts) {
    const json& value = need(p, p.value, key);
    if (value != expected)
      throw InputError(p.file, fmt::format("'{}' is {}, but {} has {}: not a shard of the same run", key, value.dump(),
                                           first.file, expected.dump()));
  }
}

// Adds the counts of `from` into `to`, two objects of the same keys: integers >= 0 are summed,
// objects key by key, anything else (flags, names) must be equal. `where` names the object.
void add_counts(json& to, const json& from, const Part& part, const std::string& where) {
  if (!from.is_object() || from.size() != to.size())
    throw InputError(part.file, fmt::format("'{}' has other keys than the first shard's", where));
  for (auto& [key, value] : to.items()) {
    const std::string path = where + "." + key;
    const json& other = need(part, from, key, where + ".");
    if (value.is_number_unsigned() && other.is_number_unsigned())
      value = value.get<std::uint64_t>() + other.get<std::uint64_t>();
    else if (value.is_object())
      add_counts(value, other, part, path);
    else if (value != other)
      throw InputError(part.file, fmt::format("'{}' is {}, but the first shard has {}", path, other.dump(), value.dump()));
  }
}

double rate(double count, double seconds) { return seconds > 0.0 ? count / seconds : 0.0; }

// ---- fuzz -------------------------------------------------------------------------------

json merge_fuzz(const std::vector<Part>& parts) {
  for (const char* key : {"seed", "case_count", "triangles", "runs", "max_reproducers", "shrink_findings"})
    require_same(parts, key);
  const Part& first = parts.front();
  const json& first_gl = need(first, first.value, "gl");
  const bool gl = !first_gl.is_null();
  for (const Part& p : parts) {
    const json& g = need(p, p.value, "gl");
    if (g.is_null() == gl)
      throw InputError(p.file, fmt::format("{} --gl, but {} {}: not shards of the same run", gl ? "ran without" : "ran with",
                                           first.file, gl ? "ran with it" : "did not"));
    if (gl)
      for (const char* key : {"size", "sign", "methods"})
        if (need(p, g, key, "gl.") != need(first, first_gl, key, "gl."))
          throw InputError(p.file, fmt::format("'gl.{}' is {}, but {} has {}: not a shard of the same run", key,
                                               g.at(key).dump(), first.file, first_gl.at(key).dump()));
  }
  // The keys the summary prints, with their types (the other shards' are held to the first's).
  (void)need_count(first, first.value, "seed");
  (void)need_count(first, first.value, "triangles");
  for (const char* key : {"families", "placements", "methods"})
    if (!need(first, first.value, key).is_object())
      throw InputError(first.file, fmt::format("'{}' must be an object of tallies", key));
  for (const auto& [run, tally] : first.value.at("methods").items()) {
    (void)need_count(first, tally, "failures", "methods." + run + ".");
    if (!need(first, tally, "must_not_fail", "methods." + run + ".").is_boolean())
      throw InputError(first.file, fmt::format("'methods.{}.must_not_fail' must be true or false", run));
  }
  const std::vector<std::string> runs = need_names(first, first.value, "runs");
  const std::vector<std::string> gl_runs = gl ? need_names(first, first_gl, "methods", "gl.") : std::vector<std::string>();
  const std::uint64_t case_count = need_count(first, first.value, "case_count");
  json out = first.value;
  out["shard"] = {{"index", 1}, {"count", 1}};
  std::uint64_t cases = 0, samples = 0, redrawn = 0, lost = 0, threads = 0, gl_cases = 0;
  double seconds = 0.0, shrink_seconds = 0.0, gl_seconds = 0.0, gl_exact_seconds = 0.0, gl_shrink_seconds = 0.0;
  bool failed = false;
  json reproducers = json::array(), shards = json::array();
  for (const Part& p : parts) {
    // A shard holds exactly its cases: a file cut short (a killed job) is refused.
    const std::uint64_t expected = shard_case_count(case_count, {p.index - 1, p.count});
    const std::uint64_t held = need_count(p, p.value, "cases");
    if (held != expected)
      throw InputError(p.file, fmt::format("holds {} cases, but shard {}/{} of {} cases has {}", held, p.index, p.count,
                                           case_count, expected));
    cases += held;
    samples += need_count(p, p.value, "samples");
    redrawn += need_count(p, p.value, "redrawn_samples");
    lost += need_count(p, p.value, "lost_samples");
    threads = std::max(threads, need_count(p, p.value, "threads"));
    seconds += need_seconds(p, p.value, "seconds");
    shrink_seconds += need_seconds(p, p.value, "shrink_seconds");
    const json& must = need(p, p.value, "must_not_fail_failed");
    if (!must.is_boolean()) throw InputError(p.file, "'must_not_fail_failed' must be true or false");
    failed = failed || must.get<bool>();
    if (&p != &first) {
      add_counts(out["families"], need(p, p.value, "families"), p, "families");
      add_counts(out["placements"], need(p, p.value, "placements"), p, "placements");
      add_counts(out["methods"], need(p, p.value, "methods"), p, "methods");
    }
    json shard{{"file", p.file}, {"index", p.index}, {"cases", held}, {"seconds", p.value.at("seconds")},
               {"threads", p.value.at("threads")}, {"renderer", nullptr}};
    if (gl) {
      const json& g = p.value.at("gl");
      const std::uint64_t gl_held = need_count(p, g, "cases", "gl.");
      if (gl_held != expected)
        throw InputError(p.file, fmt::format("'gl.cases' is {}, but shard {}/{} of {} cases has {}", gl_held, p.index,
                                             p.count, case_count, expected));
      gl_cases += gl_held;
      gl_seconds += need_seconds(p, g, "seconds", "gl.");
      gl_exact_seconds += need_seconds(p, g, "exact_seconds", "gl.");
      gl_shrink_seconds += need_seconds(p, g, "shrink_seconds", "gl.");
      shard["renderer"] = need(p, g, "renderer", "gl.");
    }
    const json& written = need(p, p.value, "reproducers");
    if (!written.is_array()) throw InputError(p.file, "'reproducers' must be an array");
    for (const json& r : written) {
      if (!need(p, r, "run", "reproducers[].").is_string())
        throw InputError(p.file, "'reproducers[].run' must be a name");
      need_count(p, r, "case", "reproducers[].");
      reproducers.push_back(r);
    }
    shards.push_back(shard);
  }
  out["cases"] = cases;
  out["samples"] = samples;
  out["redrawn_samples"] = redrawn;
  out["lost_samples"] = lost;
  out["threads"] = threads;
  out["seconds"] = seconds;  // machine time: the shards' sum
  out["cases_per_second"] = rate(static_cast<double>(cases), seconds);
  out["shrink_seconds"] = shrink_seconds;
  out["must_not_fail_failed"] = failed;
  if (gl) {
    json& g = out["gl"];
    g["cases"] = gl_cases;
    g["seconds"] = gl_seconds;
    g["cases_per_second"] = rate(static_cast<double>(gl_cases), gl_seconds);
    g["exact_seconds"] = gl_exact_seconds;
    g["shrink_seconds"] = gl_shrink_seconds;
  }

  // A run writes the reproducers of the first max_reproducers failing cases of each method
  // run, by case index: the exact part's runs in the order of "runs", then the GL methods in
  // the order of gl.methods. Each shard wrote the first ones of its own cases, a superset of
  // the whole run's among them; keep the whole run's, in its order.
  const auto rank = [&](const json& r) {
    const std::string run = r.at("run").get<std::string>();
    const auto exact_at = std::find(runs.begin(), runs.end(), run);
    if (exact_at != runs.end()) return std::make_tuple(0, r.at("case").get<std::uint64_t>(), exact_at - runs.begin());
    return std::make_tuple(1, r.at("case").get<std::uint64_t>(), std::find(gl_runs.begin(), gl_runs.end(), run) - gl_runs.begin());
  };
  std::stable_sort(reproducers.begin(), reproducers.end(),
                   [&](const json& a, const json& b) { return rank(a) < rank(b); });
  const std::uint64_t max_reproducers = need_count(first, first.value, "max_reproducers");
  std::map<std::string, std::uint64_t> kept_per_run;
  json kept = json::array();
  for (const json& r : reproducers)
    if (kept_per_run[r.at("run").get<std::string>()]++ < max_reproducers) kept.push_back(r);
  out["reproducers"] = kept;
  out["shards"] = shards;
  return out;
}

// ---- bench (docs/bench.md, "Shards and their merge") -----------------------------------------

// The merged scenes' totals (bench's totals_json; every shard file is checked by then).
json totals_of(const json& scenes) {
  std::uint64_t skipped = 0, runs = 0, failed = 0, failed_scenes = 0;
  for (const json& s : scenes) {
    if (!s.at("skipped").is_null()) ++skipped;
    if (s.contains("failure") && !s.at("failure").is_null()) ++failed_scenes;
    for (const json& r : s.at("runs")) {
      ++runs;
      if (r.at("failed").get<bool>()) ++failed;
    }
  }
  return {{"scenes", scenes.size()},
          {"skipped_scenes", skipped},
          {"runs", runs},
          {"failed_runs", failed},
          {"failed_scenes", failed_scenes}};
}

json without_date(json environment) {
  if (environment.is_object()) environment.erase("date");
  return environment;
}

json merge_bench(const std::vector<Part>& parts) {
  // Each file whole and consistent first (cli/bench_file.h): its scenes are then exactly its
  // shard's, in index order, and every key below is there with its type.
  for (const Part& p : parts) {
    const BenchFileStatus status = check_bench_file(p.value, p.file);
    // A shard that was interrupted (its bench.json is written after every scene, with
    // "complete": false until the end) is refused: the merge would be a run with scenes missing.
    if (!status.complete)
      throw InputError(p.file, fmt::format("'complete' is false: shard {}/{} was interrupted after {} of its {} scenes; "
                                           "run it again (bench --from {} shows what it finished)",
                                           p.index, p.count, status.scenes, status.shard_scenes, p.file));
  }
  for (const char* key : {"suite", "scene_count", "size", "warm_up_frames", "frames", "methods"}) require_same(parts, key);
  const Part& first = parts.front();
  std::vector<const json*> scenes;  // by index: shard k's j-th scene has index (k - 1) + j N
  double seconds = 0.0;
  bool environments_differ = false;
  json environments = json::array();
  for (const Part& p : parts) {
    for (const json& s : p.value.at("scenes")) scenes.push_back(&s);
    seconds += p.value.at("seconds").get<double>();
    const json& environment = p.value.at("environment");
    environments.push_back(environment);
    environments_differ = environments_differ || without_date(environment) != without_date(first.value.at("environment"));
  }
  std::sort(scenes.begin(), scenes.end(),
            [](const json* a, const json* b) { return a->at("index").get<std::uint64_t>() < b->at("index").get<std::uint64_t>(); });
  json out = first.value;
  json merged = json::array();
  for (const json* scene : scenes) merged.push_back(*scene);
  out["shard"] = {{"index", 1}, {"count", 1}};
  out["complete"] = true;
  out["seconds"] = seconds;  // machine time: the shards' sum
  out["totals"] = totals_of(merged);
  out["scenes"] = std::move(merged);
  if (environments_differ) out["environment"]["shards"] = environments;
  return out;
}

// ---- the command ---------------------------------------------------------------------------

int run_merge(const MergeOptions& options) {
  std::vector<Part> parts;
  for (const std::string& file : options.files) parts.push_back({file, read_json_object(file)});
  for (const Part& p : parts)
    if (!p.value.contains("schema"))
      throw InputError(p.file, fmt::format("no key 'schema': not a file of fuzz --json ({}) or of bench ({})",
                                           kFuzzSchema, kBenchSchema));
  const Part& first = parts.front();
  const json& schema = first.value.at("schema");
  if (schema != kFuzzSchema && schema != kBenchSchema)
    throw InputError(first.file, fmt::format("schema {} is neither {} (fuzz --json) nor {} (bench.json)", schema.dump(),
                                             kFuzzSchema, kBenchSchema));
  for (Part& p : parts) {
    const json& s = need(p, p.value, "schema");
    if (s != schema)
      throw InputError(p.file, fmt::format("schema {}, but {} has {}: only files of one kind merge", s.dump(), first.file,
                                           schema.dump()));
    read_shard(p);
  }
  check_shards(parts);
  const bool fuzz = schema == kFuzzSchema;
  const json merged = fuzz ? merge_fuzz(parts) : merge_bench(parts);
  write_json_file(options.json_file, merged);
  if (fuzz) {
    fmt::print("merged {} shards of fuzz seed {}: {} cases of {} triangles{}; {}\n", parts.size(),
               merged.at("seed").get<std::uint64_t>(), merged.at("cases").get<std::uint64_t>(),
               merged.at("triangles").get<std::uint64_t>(), merged.at("gl").is_null() ? "" : ", GL methods too",
               merged.at("must_not_fail_failed").get<bool>() ? "A METHOD THAT MUST NOT FAIL FAILED"
                                                          : "no method that must not fail failed");
    for (const auto& [run, tally] : merged.at("methods").items())
      fmt::print("  {:<16} {:>8} failures{}\n", run, tally.at("failures").get<std::uint64_t>(),
                 tally.at("must_not_fail").get<bool>() ? " (must not fail)" : "");
  } else {
    const json& totals = merged.at("totals");
    const std::uint64_t failed_scenes = totals.at("failed_scenes").get<std::uint64_t>();
    fmt::print("merged {} shards of bench {}: {} scenes ({} skipped{}), {} runs, {} failed\n", parts.size(),
               merged.at("suite").get<std::string>(), totals.at("scenes").get<std::uint64_t>(),
               totals.at("skipped_scenes").get<std::uint64_t>(),
               failed_scenes > 0 ? fmt::format(", {} FAILED", failed_scenes) : std::string(),
               totals.at("runs").get<std::uint64_t>(), totals.at("failed_runs").get<std::uint64_t>());
  }
  fmt::print("wrote {}{}\n", options.json_file,
             fuzz ? "" : " (shadowcert bench --from it --out DIR writes its tables, plots and report)");
  // A bench fails a check, as the whole run would, with a failed run or a scene that failed.
  const bool check_failed = fuzz ? merged.at("must_not_fail_failed").get<bool>()
                                 : merged.at("totals").at("failed_runs").get<std::uint64_t>() > 0 ||
                                       merged.at("totals").at("failed_scenes").get<std::uint64_t>() > 0;
  return check_failed ? kExitCheckFailed : kExitOk;
}

}  // namespace

void add_merge_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<MergeOptions>();
  CLI::App* cmd = app.add_subcommand(
      "merge",
      "Merge the JSON files of the shards of one fuzz campaign or bench run (--shard K/N) into the whole run's "
      "(docs/batch-runs.md). Exit 1 when the merged run fails a check (as the whole run would)");
  cmd->add_option("files", options->files, "The shards' files: fuzz --json files, or bench.json files")
      ->required();
  cmd->add_option("--json", options->json_file, "Write the merged JSON to FILE")->required();
  cmd->callback([options, &exit_code] { exit_code = run_merge(*options); });
}

}  // namespace shadowcert::cli
