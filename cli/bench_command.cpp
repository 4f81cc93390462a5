#include "cli/bench_command.h"

#include <fmt/core.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <memory>
#include <new>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "cli/bench_file.h"
#include "cli/bench_outputs.h"
#include "cli/comparison_json.h"
#include "cli/exit_code.h"
#include "cli/frame_timing_output.h"
#include "cli/option_values.h"
#include "core/input_error.h"
#include "gpu/egl_context.h"
#include "gpu/gl_environment_error.h"
#include "gpu/png_image.h"
#include "io/output_file.h"
#include "pipeline/bench_suite.h"

#ifndef SHADOWCERT_SOURCE_DIR
#define SHADOWCERT_SOURCE_DIR ""
#endif
#ifndef SHADOWCERT_BUILD_TYPE
#define SHADOWCERT_BUILD_TYPE ""
#endif

namespace shadowcert::cli {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kWarmUpFrames = 2;
constexpr std::size_t kMaxFrames = 100000;
constexpr const char* kDefaultSize = "160x120";

struct BenchCommandOptions {
  std::vector<std::string> scenes;
  std::string suite;  // empty: default, or "scenes" when SCENES are given
  std::string methods;
  std::string size = kDefaultSize;
  std::size_t frames = 10;
  std::string out = "out/bench";
  std::string json_file;
  std::string shard;
  std::optional<int> device;
  std::optional<double> light_radius;
  std::optional<double> light_angle;  // degrees: a directional light's angular radius
  std::string shared_data;
  std::string from;
  bool no_plots = false;
  unsigned threads = 0;  // --threads (0: every core)
  std::string command;  // argv, for bench.json
};

struct Shard {
  std::size_t k = 1, n = 1;
};

Shard parse_shard(const std::string& text) {
  Shard s;
  const std::size_t slash = text.find('/');
  const auto number = [&](const std::string& part, std::size_t& value) {
    if (part.empty() || part.size() > 9 || part.find_first_not_of("0123456789") != std::string::npos) return false;
    value = std::stoul(part);
    return true;
  };
  if (slash == std::string::npos || !number(text.substr(0, slash), s.k) || !number(text.substr(slash + 1), s.n) ||
      s.n == 0 || s.k == 0 || s.k > s.n)
    throw CLI::ValidationError("--shard", "must be K/N with 1 <= K <= N (shard K of N: the scenes whose index i in "
                                          "the suite has i % N == K - 1), got \"" + text + "\"");
  return s;
}

// The output of `command` (its first line), or nullopt when it fails.
std::optional<std::string> command_line_output(const std::string& command) {
  FILE* pipe = popen((command + " 2>/dev/null").c_str(), "r");
  if (pipe == nullptr) return std::nullopt;
  std::string out;
  char buffer[512];
  while (std::fgets(buffer, sizeof buffer, pipe) != nullptr) out += buffer;
  const int status = pclose(pipe);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) return std::nullopt;
  return out;
}

std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return text;
}

nlohmann::json environment_json(const gpu::EglContext& context, bool software) {
  nlohmann::json git_commit = nullptr, git_dirty = nullptr;
  const std::string source = SHADOWCERT_SOURCE_DIR;
  if (!source.empty()) {
    if (const std::optional<std::string> head = command_line_output("git -C " + shell_quote(source) + " rev-parse HEAD")) {
      std::string commit = *head;
      while (!commit.empty() && (commit.back() == '\n' || commit.back() == '\r')) commit.pop_back();
      git_commit = commit;
      if (const std::optional<std::string> status =
              command_line_output("git -C " + shell_quote(source) + " status --porcelain --untracked-files=no"))
        git_dirty = !status->empty();
    }
  }
  return {{"renderer", context.renderer()},
          {"gl_version", context.version()},
          {"device", context.device()},
          {"software_renderer", software},
          {"stage_sync", software ? "finish" : "none"},
          {"build_type", std::string(SHADOWCERT_BUILD_TYPE).empty() ? nlohmann::json(nullptr)
                                                                     : nlohmann::json(SHADOWCERT_BUILD_TYPE)},
          {"git_commit", git_commit},
          {"git_dirty", git_dirty},
          {"date", utc_now()},
          {"version", "shadowcert 0.1.0"},
          {"host", {{"cpus", std::thread::hardware_concurrency()},
                    // The TBB threads the exact image and the ray tracer ran on (--threads).
                    {"threads", tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism)}}}};
}

nlohmann::json timing_json(const BenchRun& b, bool synchronised) {
  nlohmann::json gpu_ms = nlohmann::json::object(), cpu_ms = nlohmann::json::object();
  for (gpu::RenderStage stage : b.timing.stages) {
    const std::string name(gpu::render_stage_name(stage));
    gpu_ms[name] = timing_summary_json(b.timing.gpu(stage));
    if (synchronised) cpu_ms[name] = timing_summary_json(b.timing.wall(stage));
  }
  gpu_ms["frame"] = timing_summary_json(b.timing.frame_gpu);
  cpu_ms["frame"] = timing_summary_json(b.timing.frame_cpu);
  return {{"frame_ms", timing_summary_json(synchronised ? b.timing.frame_cpu : b.timing.frame_gpu)},
          {"gpu_ms", gpu_ms},
          {"cpu_ms", cpu_ms},
          {"build_ms", b.build_ms}};
}

nlohmann::json parameter_json(const BenchRun& b) {
  const BenchVariant& v = b.variant;
  nlohmann::json p = nlohmann::json::object();
  if (v.family == BenchFamily::ray_traced) {
    p["mode"] = raytrace::build_mode_name(ray_traced_entry(v.ray_traced).mode);
    return p;
  }
  if (v.family != BenchFamily::edges && gpu::builds_volume_on_gpu(v.method)) p["sign"] = gpu::sign_mode_name(v.sign);
  if (gpu::uses_shadow_map(v.method)) p["shadow_map_size"] = v.shadow_map_size;
  if (v.method == gpu::ShadowMethod::pcf) p["pcf_kernel"] = v.pcf_kernel;
  if (v.method == gpu::ShadowMethod::pcss) p["light_radius"] = b.light_radius;
  if (v.method == gpu::ShadowMethod::smooth || v.method == gpu::ShadowMethod::smooth_gpu) p["epsilon"] = v.epsilon;
  if (v.family == BenchFamily::edges) {
    p["filter"] = gpu::edge_filter_name(v.edge_filter);
    if (b.edges) {
      p["profile_threshold"] = b.edges->profile_threshold;
      p["inner_threshold"] = b.edges->inner_threshold;
    }
    return p;
  }
  if (v.method == gpu::ShadowMethod::smoothie) {
    p["smoothie_width"] = b.smoothie_width;
    p["smoothie_width_in_r"] = v.smoothie_width_in_r;
    p["smoothie_space"] = smoothie_space_name(v.smoothie_space);
  }
  return p;
}

// "cs/float" -> "cs-float": a file name.
std::string file_id(const std::string& id) {
  std::string out = id;
  for (char& c : out)
    if (c == '/' || c == ' ') c = '-';
  return out;
}

nlohmann::json run_json(const BenchRun& b, bool synchronised, const nlohmann::json& images) {
  const MethodRun& r = b.run;
  nlohmann::json error{{"hard_errors", r.sum(&PixelComparison::hard_errors)},
                       {"ambiguous", r.sum(&PixelComparison::ambiguous)},
                       {"agree", r.sum(&PixelComparison::agree)},
                       {"coverage_errors", r.sum(&PixelComparison::coverage_errors)},
                       {"lit_errors", r.sum(&PixelComparison::lit_errors)},
                       {"count_errors", r.sum(&PixelComparison::count_errors)},
                       {"closed", nullptr},
                       {"volume_triangles", nullptr},
                       {"capacity_error", nullptr},
                       {"soft", nullptr},
                       {"analytic", nullptr},
                       {"contour", nullptr},
                       {"edges", nullptr},
                       {"images", images}};
  if (const std::optional<bool> closed =
          b.variant.family == BenchFamily::ray_traced ? std::nullopt : r.closed()) {  // rt: no volume
    error["closed"] = *closed;
    error["volume_triangles"] = r.lights.empty() ? 0 : r.lights.front().volume_triangles;
  }
  for (const LightRun& l : r.lights)
    if (!l.capacity_error.empty()) error["capacity_error"] = l.capacity_error;
  if (b.soft) error["soft"] = soft_errors_json(*b.soft);
  if (const std::optional<AnalyticCounts> a = r.analytic()) error["analytic"] = analytic_counts_json(*a);
  if (b.edges) {
    // No lit mask: the pixel figures do not apply.
    for (const char* key : {"hard_errors", "ambiguous", "agree", "coverage_errors", "lit_errors", "count_errors"})
      error[key] = nullptr;
    const auto scores = [](const EdgeMatchCounts& c) {
      return nlohmann::json{{"precision", c.precision()},     {"recall", c.recall()},     {"f1", c.f1()},
                            {"detections", c.detections},     {"true_detections", c.true_detections},
                            {"truth", c.truth}};
    };
    nlohmann::json e = scores(b.edges->pooled());
    e["tolerance"] = "1px";
    e["profile"] = scores(b.edges->profile);
    e["profile"]["threshold"] = b.edges->profile_threshold;
    e["inner"] = scores(b.edges->inner);
    e["inner"]["threshold"] = b.edges->inner_threshold;
    error["edges"] = e;
  }
  if (b.contour)
    error["contour"] = {{"max", b.contour->max}, {"mean", b.contour->mean}, {"points", b.contour->points},
                        {"casters", b.contour->casters}};
  return {{"id", b.variant.id},
          {"method", method_of(b.variant)},
          {"family", bench_family_name(b.variant.family)},
          {"parameter", parameter_json(b)},
          {"robust", r.held_robust},
          {"failed", b.failed()},
          {"time", timing_json(b, synchronised)},
          {"error", error}};
}

// Writes `png` under dir and returns its path relative to dir.
std::string write_image(const fs::path& dir, const std::string& relative, const std::vector<std::uint8_t>& png) {
  const fs::path file = dir / relative;
  create_parent_directories(file);
  std::ofstream out(file, std::ios::binary);
  out.write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
  if (!out) throw InputError(file.string(), "write failed");
  return relative;
}

// One scene's record. `r`: its result, null for a scene that did not run (`skipped` says why)
// or that failed before its figures; `failure`: null, or what threw (failure_json).
nlohmann::json scene_json(std::size_t index, const BenchSceneSpec& spec, const BenchSceneResult* r, bool synchronised,
                          const fs::path& dir, const std::string& skipped, std::uint32_t soft_samples,
                          const nlohmann::json& failure = nullptr) {
  nlohmann::json j{{"index", index},          {"suite", spec.suite},  {"name", spec.name},
                   {"input", spec.input},     {"skipped", nullptr},   {"triangles", nullptr},
                   {"lights", nullptr},       {"size", nullptr},      {"exact_seconds", nullptr},
                   {"exact_image_seconds", nullptr},
                   {"soft_reference", nullptr}, {"analytic", nullptr}, {"edge_truth_seconds", nullptr},
                   {"seconds", 0.0},          {"failure", failure},
                   {"images", nlohmann::json::object()},            {"runs", nlohmann::json::array()}};
  if (r == nullptr) {
    if (!skipped.empty()) j["skipped"] = skipped;
    return j;
  }
  j["triangles"] = r->triangles;
  j["lights"] = r->lights;
  j["size"] = {r->width, r->height};
  j["exact_seconds"] = r->exact_seconds;
  j["exact_image_seconds"] = r->exact_image_seconds;
  if (r->soft_radius)
    j["soft_reference"] = {{"radius", *r->soft_radius},
                           {"angle_degrees", r->soft_angle_degrees},
                           {"samples", soft_samples},
                           {"seconds", r->soft_seconds}};
  if (!r->analytic_casters.empty()) {
    nlohmann::json plane = nullptr;
    if (spec.receiver_plane) {
      const Plane& p = *spec.receiver_plane;
      plane = {p.normal[0], p.normal[1], p.normal[2],
               -(p.normal[0] * p.point[0] + p.normal[1] * p.point[1] + p.normal[2] * p.point[2])};
    }
    j["analytic"] = {{"casters", r->analytic_casters}, {"seconds", r->analytic_seconds}, {"receiver_plane", plane}};
  }
  if (std::any_of(r->runs.begin(), r->runs.end(), [](const BenchRun& b) { return b.edges.has_value(); }))
    j["edge_truth_seconds"] = r->edge_truth_seconds;
  j["seconds"] = r->seconds;
  const std::string folder = "images/" + spec.suite + "/" + spec.name + "/";
  if (!r->exact_mask.pixels.empty()) {
    j["images"]["exact_mask"] = write_image(dir, folder + "exact_mask.png", gpu::encode_png(r->exact_mask));
    j["images"]["exact_counts"] = write_image(dir, folder + "exact_counts.png", gpu::encode_png(r->exact_counts));
    j["images"]["exact_ambiguous"] =
        write_image(dir, folder + "exact_ambiguous.png", gpu::encode_png(r->exact_ambiguous));
    j["count_scale"] = r->count_scale;
  }
  for (const BenchRun& b : r->runs) {
    nlohmann::json images = nlohmann::json::object();
    if (!b.overlay.pixels.empty())
      images["overlay"] = write_image(dir, folder + file_id(b.variant.id) + "_overlay.png", gpu::encode_png(b.overlay));
    if (!b.soft_error.pixels.empty())
      images["soft_error"] =
          write_image(dir, folder + file_id(b.variant.id) + "_soft_error.png", gpu::encode_png(b.soft_error));
    j["runs"].push_back(run_json(b, synchronised, images));
  }
  return j;
}

void write_text(const fs::path& file, const std::string& text) {
  create_parent_directories(file);
  std::ofstream out(file, std::ios::binary);
  if (!out) throw InputError(file.string(), "cannot open for writing");
  out << text;
  if (!out) throw InputError(file.string(), "write failed");
}

// The interpreter that runs tools/bench_plots.py: SHADOWCERT_PYTHON, else the first of python3
// and /usr/bin/python3 (Debian's, where python3-matplotlib installs) that imports matplotlib.
std::optional<std::string> plotting_python() {
  std::vector<std::string> candidates;
  if (const char* env = std::getenv("SHADOWCERT_PYTHON"); env != nullptr && *env != '\0') candidates.emplace_back(env);
  candidates.emplace_back("python3");
  candidates.emplace_back("/usr/bin/python3");
  for (const std::string& python : candidates)
    if (command_line_output(shell_quote(python) + " -c 'import matplotlib'")) return python;
  return std::nullopt;
}

// tools/bench_plots.py: SHADOWCERT_BENCH_PLOTS, else the source tree's, else beside the binary
// (an install's share/shadowcert/).
std::optional<fs::path> plots_script() {
  if (const char* env = std::getenv("SHADOWCERT_BENCH_PLOTS"); env != nullptr && *env != '\0') return fs::path(env);
  std::vector<fs::path> candidates;
  if (!std::string(SHADOWCERT_SOURCE_DIR).empty()) candidates.push_back(fs::path(SHADOWCERT_SOURCE_DIR) / "tools/bench_plots.py");
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) candidates.push_back(self.parent_path().parent_path() / "share/shadowcert/bench_plots.py");
  for (const fs::path& c : candidates)
    if (fs::exists(c)) return c;
  return std::nullopt;
}

// The plots (DIR/plots/*.png and DIR/plots/index.json), or why there are none. A failing script
// is a bug of ours: thrown (exit 3) after every other output is written.
std::string make_plots(const fs::path& dir, bool no_plots) {
  if (no_plots) return "plots not drawn: --no-plots";
  const std::optional<fs::path> script = plots_script();
  if (!script) return "plots not drawn: tools/bench_plots.py not found (set SHADOWCERT_BENCH_PLOTS)";
  const std::optional<std::string> python = plotting_python();
  if (!python)
    return "plots not drawn: no python3 with matplotlib (Debian: apt install python3-matplotlib; or set "
           "SHADOWCERT_PYTHON)";
  fs::remove_all(dir / "plots");
  const std::string command = shell_quote(*python) + " " + shell_quote(script->string()) + " " +
                              shell_quote((dir / "bench.json").string()) + " " + shell_quote((dir / "plots").string());
  const int status = std::system(command.c_str());
  if (status != 0)
    throw std::runtime_error("bench: the plotting script failed (" + command + ", status " + std::to_string(status) + ")");
  return {};
}

// Writes `value` to `file` through FILE.partial and a rename, so that a reader, or a run killed
// meanwhile, finds the previous file or the new one whole, never half of one.
void replace_json_file(const fs::path& file, const nlohmann::json& value) {
  const fs::path partial = file.string() + ".partial";
  write_json_file(partial, value);
  std::error_code ec;
  fs::rename(partial, file, ec);
  if (ec) throw InputError(file.string(), "cannot replace it with " + partial.string() + ": " + ec.message());
}

void write_outputs(const nlohmann::json& bench, const fs::path& dir, bool no_plots, std::string& plots_note) {
  replace_json_file(dir / "bench.json", bench);
  write_text(dir / "bench.csv", bench_csv(bench));
  write_text(dir / "bench.md", bench_markdown(bench));
  std::string plot_error;
  try {
    plots_note = make_plots(dir, no_plots);
  } catch (const std::runtime_error& e) {
    plot_error = e.what();
    plots_note = "plots FAILED: " + plot_error;
  }
  write_text(dir / "report.html", bench_report_html(bench, dir, plots_note));
  if (!plot_error.empty()) throw std::runtime_error(plot_error);
}

// bench.json's "totals" of the scenes this command wrote (scene_json's).
nlohmann::json totals_json(const nlohmann::json& scenes) {
  std::size_t skipped = 0, runs = 0, failed = 0, failed_scenes = 0;
  for (const nlohmann::json& s : scenes) {
    if (!s.at("skipped").is_null()) ++skipped;
    if (!s.at("failure").is_null()) ++failed_scenes;
    for (const nlohmann::json& r : s.at("runs")) {
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

// A scene's "failure" record (docs/bench.md, "A scene that fails"): the run that threw (null:
// loading the scene or its references), the kind of error by the exit code it would have
// given alone (input and environment: 2, internal: 3, cli/exit_code.h), and its message.
nlohmann::json failure_json(const std::string& run, const char* kind, const std::string& message) {
  return {{"run", run.empty() ? nlohmann::json(nullptr) : nlohmann::json(run)}, {"kind", kind}, {"message", message}};
}

int run_from(const BenchCommandOptions& options) {
  std::ifstream in(options.from);
  if (!in) throw InputError(options.from, "cannot open");
  nlohmann::json bench;
  try {
    bench = nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(options.from, std::string("not JSON: ") + e.what());
  }
  if (!bench.is_object() || !bench.contains("schema"))
    throw InputError(options.from, std::string("not a bench.json (no key 'schema'; ") + kBenchSchema + ")");
  // Every key the outputs read, with its type: exit 2 naming the key, never a read of a key
  // that is not there (cli/bench_file.h).
  const BenchFileStatus status = check_bench_file(bench, options.from);
  if (!status.complete)
    fmt::print(stderr,
               "bench: {} is incomplete (\"complete\": false): {} of its shard's {} scenes, an interrupted run; "
               "the outputs show those\n",
               options.from, status.scenes, status.shard_scenes);
  const fs::path dir(options.out);
  const fs::path from_dir = fs::absolute(fs::path(options.from)).parent_path();
  // The images go with the tables: the report reads them from --out. (Copied into a folder made
  // first: fs::copy into a missing --out failed, exit 3.)
  if (fs::weakly_canonical(from_dir) != fs::weakly_canonical(fs::absolute(dir)) && fs::exists(from_dir / "images")) {
    std::error_code ec;
    fs::create_directories(dir / "images", ec);
    if (!ec)
      fs::copy(from_dir / "images", dir / "images", fs::copy_options::recursive | fs::copy_options::update_existing, ec);
    if (ec) throw InputError((dir / "images").string(), "cannot copy the images of " + options.from + " here: " + ec.message());
  }
  std::string plots_note;
  write_outputs(bench, dir, options.no_plots, plots_note);
  fmt::print("bench: wrote {0}/bench.json, bench.csv, bench.md, report.html{1}\n", dir.string(),
             plots_note.empty() ? ", plots/" : "; " + plots_note);
  return kExitOk;
}

int run_bench(const BenchCommandOptions& options) {
  if (!options.from.empty()) {
    if (!options.scenes.empty() || !options.suite.empty())
      throw CLI::ValidationError("--from", "rewrites the outputs of a bench.json: no SCENES or --suite with it");
    return run_from(options);
  }
  const std::unique_ptr<tbb::global_control> thread_cap = thread_limit(options.threads);
  const auto start = std::chrono::steady_clock::now();
  const bool suite_given = !options.suite.empty();
  if (!options.scenes.empty() && suite_given && options.suite != "real")
    throw CLI::ValidationError("--suite", "SCENES replace the suite's list: only --suite real takes them (meshes "
                                          "framed over a floor), got --suite " + options.suite);
  std::vector<BenchVariant> variants;
  try {
    variants = select_bench_variants(options.methods);
  } catch (const std::invalid_argument& e) {
    throw CLI::ValidationError("--methods", e.what());
  }
  if (options.frames < 1 || options.frames > kMaxFrames)
    throw CLI::ValidationError("--frames", fmt::format("must be in [1, {}], got {}", kMaxFrames, options.frames));
  if (options.light_radius && (!std::isfinite(*options.light_radius) || !(*options.light_radius > 0.0)))
    throw CLI::ValidationError("--light-radius",
                               fmt::format("must be finite and > 0 (world units), got {}", *options.light_radius));
  if (options.light_angle) check_light_angle(*options.light_angle);
  Camera size_camera;
  apply_image_size(options.size, size_camera);
  const Shard shard = options.shard.empty() ? Shard{} : parse_shard(options.shard);

  BenchPaths paths;
  paths.source_dir = SHADOWCERT_SOURCE_DIR;
  paths.shared_data = options.shared_data.empty() ? paths.source_dir / "../shared/data" : fs::path(options.shared_data);
  const std::string suite = !options.scenes.empty() ? (options.suite == "real" ? "real" : "scenes")
                            : suite_given           ? options.suite
                                                    : "default";
  const std::vector<BenchSceneSpec> specs = options.scenes.empty() ? bench_suite(suite, paths)
                                                                   : bench_scene_files(options.scenes, suite == "real");
  // A given file that is not there is the user's to fix, before anything runs.
  for (const BenchSceneSpec& s : specs)
    if (suite == "scenes" || (suite == "real" && !options.scenes.empty()))
      if (!fs::exists(s.file)) throw InputError(s.input, "no such file");
  if (specs.empty()) throw InputError(suite, "the suite has no scene (is data/scenes/ in the source tree?)");

  const gpu::EglContext context = gpu::open_gl_context("bench", options.device);
  const bool software = context.software();
  BenchOptions bench_options;
  bench_options.warm_up_frames = kWarmUpFrames;
  bench_options.frames = options.frames;
  bench_options.sync = software ? gpu::StageSync::finish : gpu::StageSync::none;
  bench_options.light_radius = options.light_radius.value_or(0.0);
  bench_options.light_angle_degrees = options.light_angle.value_or(0.0);  // 0: gpu::kDefaultLightAngleDegrees
  const bool verbose = isatty(fileno(stderr)) != 0;
  if (verbose) bench_options.progress = [](std::string_view line) { fmt::print(stderr, "    {}\n", line); };

  nlohmann::json run_ids = nlohmann::json::array();
  for (const BenchVariant& v : variants) run_ids.push_back(v.id);
  const fs::path dir(options.out);
  std::size_t shard_scenes = 0;
  for (std::size_t i = 0; i < specs.size(); ++i)
    if (in_shard(i, shard.k, shard.n)) ++shard_scenes;
  const auto seconds_so_far = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  // bench.json is rewritten after every scene with "complete": false (docs/bench.md, "Written as
  // it goes"), so that a run killed midway (a cluster job out of time) leaves what it finished;
  // the first write, before any scene, replaces a file an earlier run left in --out.
  nlohmann::json bench{{"schema", kBenchSchema},
                       {"command", options.command},
                       {"suite", suite},
                       {"shard", {{"index", shard.k}, {"count", shard.n}}},
                       {"scene_count", specs.size()},
                       {"size", {size_camera.width, size_camera.height}},
                       {"warm_up_frames", kWarmUpFrames},
                       {"frames", options.frames},
                       {"methods", run_ids},
                       {"environment", environment_json(context, software)},
                       {"complete", false},
                       {"seconds", 0.0},
                       {"totals", totals_json(nlohmann::json::array())},
                       {"scenes", nlohmann::json::array()}};
  replace_json_file(dir / "bench.json", bench);
  std::size_t done = 0;
  bool failed = false;
  for (std::size_t i = 0; i < specs.size(); ++i) {
    if (!in_shard(i, shard.k, shard.n)) continue;
    const BenchSceneSpec& spec = specs[i];
    ++done;
    nlohmann::json& scenes = bench["scenes"];
    if (!spec.missing.empty()) {
      fmt::print(stderr, "[{}/{}] {}/{}: skipped: {}\n", done, shard_scenes, spec.suite, spec.name, spec.missing);
      scenes.push_back(scene_json(i, spec, nullptr, software, dir, spec.missing, bench_options.soft_samples));
    } else {
      // A scene (or one of its runs) that throws is recorded with its error and the bench goes on
      // (docs/bench.md, "A scene that fails"); the runs it finished are kept.
      const auto scene_start = std::chrono::steady_clock::now();
      BenchSceneResult result;
      nlohmann::json failure = nullptr;
      try {
        const Scene scene = load_bench_scene(spec, size_camera.width, size_camera.height);
        bench_scene_into(result, scene, spec, variants, bench_options);
      } catch (const InputError& e) {
        failure = failure_json(result.running, "input", e.what());
      } catch (const gpu::GlEnvironmentError& e) {
        failure = failure_json(result.running, "environment", e.what());
      } catch (const std::bad_alloc&) {
        failure = failure_json(result.running, "environment", "out of memory");
      } catch (const std::exception& e) {
        failure = failure_json(result.running, "internal", e.what());
      }
      std::size_t scene_failed = 0;
      for (const BenchRun& b : result.runs) scene_failed += b.failed() ? 1 : 0;
      failed = failed || scene_failed > 0 || !failure.is_null();
      if (failure.is_null()) {
        fmt::print(stderr, "[{}/{}] {}/{}: {} triangles, {} runs{}, {:.1f} s\n", done, shard_scenes, spec.suite,
                   spec.name, result.triangles, result.runs.size(),
                   scene_failed > 0 ? fmt::format(", {} FAILED", scene_failed) : std::string(), result.seconds);
        scenes.push_back(scene_json(i, spec, &result, software, dir, {}, bench_options.soft_samples));
      } else {
        fmt::print(stderr, "[{}/{}] {}/{}: FAILED{} ({} error): {}; {} runs kept, the bench goes on\n", done,
                   shard_scenes, spec.suite, spec.name,
                   failure.at("run").is_null() ? std::string() : " in run " + failure.at("run").get<std::string>(),
                   failure.at("kind").get<std::string>(), failure.at("message").get<std::string>(), result.runs.size());
        // Before its figures (width 0: it threw loading or checking the scene) it has none.
        nlohmann::json j = scene_json(i, spec, result.width == 0 ? nullptr : &result, software, dir, {},
                                      bench_options.soft_samples, failure);
        j["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - scene_start).count();
        scenes.push_back(std::move(j));
      }
    }
    bench["seconds"] = seconds_so_far();
    bench["totals"] = totals_json(scenes);
    replace_json_file(dir / "bench.json", bench);
  }
  bench["complete"] = true;
  bench["seconds"] = seconds_so_far();
  const double seconds = bench["seconds"].get<double>();
  std::string plots_note;
  if (!options.json_file.empty()) write_json_file(options.json_file, bench);
  write_outputs(bench, dir, options.no_plots, plots_note);
  const nlohmann::json& totals = bench["totals"];
  const std::size_t failed_scenes = totals.at("failed_scenes").get<std::size_t>();
  fmt::print("bench {}{}: {} scenes ({} skipped{}), {} runs, {} failed, {:.1f} s on {}\n", suite,
             shard.n > 1 ? fmt::format(" shard {}/{}", shard.k, shard.n) : std::string(),
             totals.at("scenes").get<std::size_t>(), totals.at("skipped_scenes").get<std::size_t>(),
             failed_scenes > 0 ? fmt::format(", {} FAILED", failed_scenes) : std::string(),
             totals.at("runs").get<std::size_t>(), totals.at("failed_runs").get<std::size_t>(), seconds,
             context.renderer());
  fmt::print("  wrote {0}/bench.json, bench.csv, bench.md, report.html, images/{1}\n", dir.string(),
             plots_note.empty() ? ", plots/" : "; " + plots_note);
  if (!plots_note.empty()) fmt::print(stderr, "bench: {}\n", plots_note);
  return failed ? kExitCheckFailed : kExitOk;
}

}  // namespace

void add_bench_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<BenchCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "bench",
      "Time against error of every GL method and parameter on a suite of scenes (docs/bench.md): bench.json, "
      "bench.csv, bench.md, plots and report.html in --out. Exit 1 when a robust run has a hard error or an open "
      "volume, or a scene failed (recorded in bench.json, the bench goes on)");
  cmd->add_option("scenes", options->scenes,
                  "Scenes (.json, as they are) or meshes (framed over a floor, as the real suite frames them) in "
                  "place of a suite's list");
  cmd->add_option("--suite", options->suite,
                  "default (data/scenes/*.json but the 1M grid), hard (data/scenes/hard/*.json), real (meshes of "
                  "../shared/data framed over a floor; SCENES replace its list), analytic (uv spheres 8x4 to "
                  "256x128 and an ellipsoid under a point light and a sun), all")
      ->check(CLI::IsMember({"default", "hard", "real", "analytic", "all"}));
  cmd->add_option("--methods", options->methods,
                  "Comma-separated methods (every run of each: cpu, cs, gs, ts, pertri, shadowmap, pcf, pcss, "
                  "smoothie, discrete, accurate, smooth, smooth-gpu, edges) or run ids (cs/float, shadowmap/1024, "
                  "pcf/5, smooth/0.01, smoothie/R/2, edges/sobel); default all");
  cmd->add_option("--size", options->size, "Image size WxH of every scene")->capture_default_str();
  cmd->add_option("--frames", options->frames, "Timed frames per run, after 2 warm-up frames")->capture_default_str();
  cmd->add_option("--out", options->out, "Output folder")->capture_default_str();
  cmd->add_option("--json", options->json_file, "Also write bench.json here");
  cmd->add_option("--shard", options->shard,
                  "K/N: only the scenes whose index i in the suite has i % N == K - 1 (1 <= K <= N); the shards' "
                  "bench.json files merge into the whole run's (docs/bench.md)");
  cmd->add_option("--light-radius", options->light_radius,
                  "The area light's radius R in world units: the soft reference, pcss and the smoothie widths R/4, "
                  "R/2, R (default 1% of each scene's bounding-box diagonal)");
  cmd->add_option("--light-angle", options->light_angle,
                  "A directional light's angular radius in degrees, in (0, 90): its soft reference and pcss (default "
                  "0.573, atan 0.01, whatever the scene's scale)");
  cmd->add_option("--shared-data", options->shared_data,
                  "Folder of the real suite's developer meshes (default: ../shared/data beside the source tree); its bundled "
                  "meshes are read from data/meshes/");
  cmd->add_option("--from", options->from,
                  "Rewrite bench.csv, bench.md, the plots and report.html in --out from this bench.json (a run's or "
                  "a merge's) without rendering");
  cmd->add_flag("--no-plots", options->no_plots, "Do not run tools/bench_plots.py");
  cmd->add_option("--device", options->device, "Use EGL device N (default: a hardware device, else llvmpipe)");
  cmd->add_option("--threads", options->threads, kThreadsHelp)->capture_default_str();
  cmd->callback([options, &exit_code, cmd] {
    std::string command = "shadowcert bench";
    for (const std::string& s : options->scenes) command += " " + s;
    for (const CLI::Option* o : cmd->get_options()) {
      if (o->get_name().empty() || o->get_name()[0] != '-' || o->count() == 0 || o->get_name() == "--help") continue;
      command += " " + o->get_name();
      if (o->get_items_expected_max() == 0) continue;  // a flag
      for (const std::string& v : o->results()) command += " " + v;
    }
    options->command = command;
    exit_code = run_bench(*options);
  });
}

}  // namespace shadowcert::cli
