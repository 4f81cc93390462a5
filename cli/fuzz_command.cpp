#include "cli/fuzz_command.h"

#include <fmt/core.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <stop_token>
#include <string>
#include <thread>
#include <vector>

#include "cli/exit_code.h"
#include "campaign/gl_campaign.h"
#include "cli/option_values.h"
#include "cli/wall_clock.h"
#include "io/output_file.h"
#include "pipeline/scene_comparison.h"
#include "campaign/soup_campaign.h"
#include "campaign/reproducer.h"
#include "campaign/campaign_run.h"
#include "campaign/case_shard.h"

namespace shadowcert::cli {
namespace {

namespace fs = std::filesystem;

// How often progress is shown: a terminal line is redrawn in place every quarter second; a
// log (stderr not a terminal) gets one line per second, so short runs print none.
constexpr std::chrono::milliseconds kTerminalProgressPeriod{250};
constexpr std::chrono::milliseconds kLogProgressPeriod{1000};
// Triangles per case beyond which a campaign is no longer a random-soup campaign but a benchmark.
constexpr std::uint32_t kMaxTriangles = 1'000'000;

struct FuzzOptions {
  std::uint64_t seed = 1;
  std::uint64_t cases = 10'000;
  std::string shard;  // --shard K/N (docs/batch-runs.md); empty: the whole campaign
  std::uint32_t triangles = 100;
  std::string methods = "all";
  bool gl = false;
  std::string out_dir = "fuzz-reproducers";
  std::string json_file;
  unsigned threads = 0;  // 0: every core
  std::size_t max_reproducers = 4;
  bool shrink_findings = false;
  std::string gl_methods = "cpu,cs,gs,ts,pertri";
  std::string gl_size = "64x48";
  std::string gl_scenes = "soups";  // --gl-scenes soups|hard (campaign/gl_campaign.h GlSceneSource)
  std::string sign = "exact";  // --sign exact|float (gpu/sign_mode.h)
  std::optional<int> device;
};


// Shows the progress of work running on the calling thread: a line on stderr from a helper
// thread, until destroyed. (The work stays on the calling thread: GL contexts are per thread.)
class ProgressLine {
 public:
  ProgressLine(std::string what, std::uint64_t total, const std::atomic<std::uint64_t>& done)
      : thread_([this, what = std::move(what), total, &done](std::stop_token stop) { show(stop, what, total, done); }) {}
  ~ProgressLine() {
    thread_.request_stop();
    wake_.notify_all();
  }
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

 private:
  void show(std::stop_token stop, const std::string& what, std::uint64_t total,
            const std::atomic<std::uint64_t>& done) {
    const auto start = Clock::now();
    const bool terminal = isatty(fileno(stderr)) != 0;
    const auto period = terminal ? kTerminalProgressPeriod : kLogProgressPeriod;
    bool shown = false;
    std::unique_lock lock(mutex_);
    while (!wake_.wait_for(lock, stop, period, [] { return false; })) {
      if (stop.stop_requested()) break;
      const std::uint64_t n = done.load();
      const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
      const double rate = seconds > 0.0 ? static_cast<double>(n) / seconds : 0.0;
      const double left = rate > 0.0 ? static_cast<double>(total - n) / rate : 0.0;
      const std::string line =
          fmt::format("{}: {}/{} cases, {:.0f} cases/s, {:.0f} s left", what, n, total, rate, left);
      if (terminal)
        fmt::print(stderr, "\r{:<70}", line);
      else
        fmt::print(stderr, "{}\n", line);
      std::fflush(stderr);
      shown = true;
    }
    if (shown && terminal) fmt::print(stderr, "\r{:<70}\r", "");
  }

  std::mutex mutex_;
  std::condition_variable_any wake_;
  std::jthread thread_;  // last: started once the members it uses exist
};

// Runs the campaign on this thread and shows its progress on stderr meanwhile.
CampaignResult run_with_progress(CampaignOptions& campaign) {
  std::atomic<std::uint64_t> done{0};
  campaign.progress = &done;
  const ProgressLine progress("fuzz", shard_case_count(campaign.cases, campaign.shard), done);
  return run_campaign(campaign);
}

std::string family_list(const std::vector<std::uint64_t>& counts) {
  std::string s;
  for (std::size_t i = 0; i < counts.size(); ++i)
    s += fmt::format("{}{} {}", i ? ", " : "", family_name(static_cast<SoupFamily>(i)), counts[i]);
  return s;
}

std::string placement_list(const std::vector<std::uint64_t>& counts) {
  std::string s;
  for (std::size_t i = 0; i < counts.size(); ++i)
    s += fmt::format("{}{} {}", i ? ", " : "", placement_name(static_cast<LightPlacement>(i)), counts[i]);
  return s;
}

void print_summary(const FuzzOptions& options, const CampaignOptions& campaign, const CampaignResult& result,
                   unsigned threads) {
  const std::string shard =
      campaign.shard.count > 1
          ? fmt::format(" (shard {}/{} of {} cases)", campaign.shard.index + 1, campaign.shard.count, campaign.cases)
          : std::string();
  fmt::print("shadowcert fuzz: seed {}, {} cases{} of {} triangles, {} runs, {} threads\n", campaign.seed, result.cases,
             shard, campaign.triangles, campaign.runs.size(), threads);
  fmt::print("  families: {}\n", family_list(result.cases_by_family));
  fmt::print("  lights:   {}\n", placement_list(result.cases_by_placement));
  fmt::print("  {:<16}{:>5}{:>10}{:>9}{:>8}{:>9}{:>11}{:>14}{:>16}\n", "run", "must", "failures", "closure", "counts",
             "decided", "sign-diff", "light-on-tri", "exact-mismatch");
  for (std::size_t r = 0; r < campaign.runs.size(); ++r) {
    const CampaignRunTally& t = result.runs[r];
    fmt::print("  {:<16}{:>5}{:>10}{:>9}{:>8}{:>9}{:>11}{:>14}{:>16}\n", campaign_run_name(campaign.runs[r]),
               must_not_fail(campaign.runs[r]) ? "yes" : "no", t.failures, t.closure_failures, t.count_failures,
               t.decided_sign_error_cases, t.sign_disagreement_cases, t.light_on_triangle_cases,
               t.exact_mismatch_cases);
  }
  const double rate = result.seconds > 0.0 ? static_cast<double>(result.cases) / result.seconds : 0.0;
  const std::uint64_t checks = result.runs.empty() ? 0 : result.runs.front().checks;
  fmt::print(
      "  (cases per column; counts = a pair whose crossings miss the run's claimed count, or a sign its\n"
      "   precision decides wrong; exact-mismatch = crossings != n(B) - n(A), docs/campaign.md)\n");
  fmt::print(
      "{} cases in {:.2f} s: {:.0f} cases/s on {} threads; {:.1f} sample points and {:.1f} compared pairs "
      "per case\n",
      result.cases, result.seconds, rate, threads,
      result.cases ? static_cast<double>(result.samples) / static_cast<double>(result.cases) : 0.0,
      result.cases ? static_cast<double>(checks) / static_cast<double>(result.cases) : 0.0);
  (void)options;
}

// One reproducer per shrunk failure: written, read back and replayed as `certify` would.
struct WrittenReproducer {
  std::string run;
  std::uint64_t case_index = 0;
  std::string failure;
  std::size_t original_triangles = 0, triangles = 0;
  fs::path json;
  std::string command;
  bool replayed = false;
};

WrittenReproducer write_reproducer(const FuzzOptions& options, const CampaignOptions& campaign,
                                   const ShrunkFailure& shrunk) {
  const CampaignRun& run = campaign.runs[shrunk.failure.run];
  CampaignReproducer r;
  r.soup = shrunk.soup;
  r.light = shrunk.original.light;
  r.method = run.method;
  r.precision = run.precision;
  r.failure = shrunk.failure.kind == CampaignFailureKind::closure ? "closure" : "counts";
  if (shrunk.failure.kind == CampaignFailureKind::counts) {
    const std::optional<CheckedPair>& pair =
        shrunk.verdict.first_exact_mismatch ? shrunk.verdict.first_exact_mismatch : shrunk.verdict.first_count_failure;
    if (pair) r.points = {pair->from, pair->to};
  }
  r.status = must_not_fail(run) ? "open" : "finding";
  r.seed = campaign.seed;
  r.case_index = shrunk.failure.index;
  r.family = std::string(family_name(shrunk.original.kind.family));
  r.placement = std::string(placement_name(shrunk.original.kind.light));
  r.original_triangles = shrunk.original.soup.triangles.size();
  const std::string name = fmt::format("{}-s{}-c{}", campaign_run_name(run), campaign.seed, shrunk.failure.index);
  WrittenReproducer w;
  w.run = campaign_run_name(run);
  w.case_index = shrunk.failure.index;
  w.failure = r.failure;
  w.original_triangles = r.original_triangles;
  w.triangles = r.soup.triangles.size();
  w.json = write_reproducer(options.out_dir, name, r);
  w.command =
      certify_command(r, fs::path(options.out_dir) / (name + ".off"), fs::path(options.out_dir) / (name + ".points"));
  // Bit for bit: what was written reads back as the very soup and light, and fails the same way.
  const CampaignReproducer back = read_reproducer(w.json);
  w.replayed = back.soup.vertices == r.soup.vertices && back.soup.triangles == r.soup.triangles &&
               back.light.position == r.light.position && replay_reproducer(back).reproduces;
  return w;
}

nlohmann::json tally_json(const CampaignRun& run, const CampaignRunTally& t) {
  nlohmann::json by_family = nlohmann::json::object(), by_placement = nlohmann::json::object();
  for (std::size_t i = 0; i < t.failures_by_family.size(); ++i)
    by_family[std::string(family_name(static_cast<SoupFamily>(i)))] = t.failures_by_family[i];
  for (std::size_t i = 0; i < t.failures_by_placement.size(); ++i)
    by_placement[std::string(placement_name(static_cast<LightPlacement>(i)))] = t.failures_by_placement[i];
  return {{"must_not_fail", must_not_fail(run)},
          {"failures", t.failures},
          {"closure_failures", t.closure_failures},
          {"count_failures", t.count_failures},
          {"decided_sign_error_cases", t.decided_sign_error_cases},
          {"sign_disagreement_cases", t.sign_disagreement_cases},
          {"light_on_triangle_cases", t.light_on_triangle_cases},
          {"exact_mismatch_cases", t.exact_mismatch_cases},
          {"checks", t.checks},
          {"skipped_checks", t.skipped},
          {"inconclusive_checks", t.inconclusive},
          {"failures_by_family", by_family},
          {"failures_by_placement", by_placement}};
}

std::string part_counts(const std::vector<std::uint64_t>& counts) {
  std::string s;
  for (std::size_t i = 0; i < counts.size(); ++i)
    s += fmt::format("{}{} {}", i ? ", " : "", hard_part_name(static_cast<HardPart>(i)), counts[i]);
  return s;
}

void print_gl_summary(const GlCampaignOptions& gl, const GlCampaignResult& result, const gpu::EglContext& context) {
  if (gl.scenes == GlSceneSource::hard) {
    fmt::print("GL methods: {}x{} images of hard-soup scenes (docs/campaign.md), z-fail, {} signs, on {}\n", gl.width,
               gl.height, gpu::sign_mode_name(gl.sign), context.renderer());
    fmt::print("  parts: {}\n  first light in a triangle's plane: {}; seen along a side face: {}\n",
               part_counts(result.cases_by_part), result.cases_light_on_plane, result.cases_edge_on);
  } else {
    fmt::print("GL methods: {}x{} images of each case's campaign view (docs/campaign.md), z-fail, {} signs, on {}\n",
               gl.width, gl.height, gpu::sign_mode_name(gl.sign), context.renderer());
  }
  fmt::print("  {:<16}{:>5}{:>10}{:>9}{:>12}{:>12}{:>12}{:>12}{:>10}\n", "run", "must", "failures", "closure",
             "hard-error", "hard px", "ambiguous", "agree", "capacity");
  for (std::size_t m = 0; m < gl.methods.size(); ++m) {
    const GlCampaignTally& t = result.methods[m];
    fmt::print("  {:<16}{:>5}{:>10}{:>9}{:>12}{:>12}{:>12}{:>12}{:>10}\n", gl_run_name(gl.methods[m]),
               robust(gl.methods[m]) ? "yes" : "no", t.failures, t.closure_failures, t.hard_errors,
               t.hard_error_pixels, t.ambiguous_pixels, t.agree_pixels, t.capacity_errors);
  }
  const double rate = result.seconds > 0.0 ? static_cast<double>(result.cases) / result.seconds : 0.0;
  if (gl.scenes == GlSceneSource::hard)
    for (std::size_t m = 0; m < gl.methods.size(); ++m)
      if (result.methods[m].failures > 0)
        fmt::print("  {} failures by part: {}\n", gl_run_name(gl.methods[m]), part_counts(result.methods[m].failures_by_part));
  fmt::print(
      "  (closure, hard-error, capacity: cases; hard px, ambiguous, agree: pixels summed over the cases)\n"
      "{} cases in {:.2f} s on one GL thread: {:.1f} cases/s ({:.2f} s of it exact images)\n",
      result.cases, result.seconds, rate, result.exact_seconds);
}

nlohmann::json gl_tally_json(gpu::ShadowMethod method, const GlCampaignTally& t) {
  nlohmann::json by_family = nlohmann::json::object(), by_placement = nlohmann::json::object();
  for (std::size_t i = 0; i < t.failures_by_family.size(); ++i)
    by_family[std::string(family_name(static_cast<SoupFamily>(i)))] = t.failures_by_family[i];
  for (std::size_t i = 0; i < t.failures_by_placement.size(); ++i)
    by_placement[std::string(placement_name(static_cast<LightPlacement>(i)))] = t.failures_by_placement[i];
  nlohmann::json by_part = nlohmann::json::object();
  for (std::size_t i = 0; i < t.failures_by_part.size(); ++i)
    by_part[std::string(hard_part_name(static_cast<HardPart>(i)))] = t.failures_by_part[i];
  return {{"must_not_fail", robust(method)},
          {"failures", t.failures},
          {"closure_failures", t.closure_failures},
          {"hard_errors", t.hard_errors},
          {"capacity_errors", t.capacity_errors},
          {"hard_error_pixels", t.hard_error_pixels},
          {"ambiguous_pixels", t.ambiguous_pixels},
          {"agree_pixels", t.agree_pixels},
          {"volume_triangles", t.volume_triangles},
          {"failures_by_family", by_family},
          {"failures_by_placement", by_placement},
          {"failures_by_part", by_part}};
}

int run_fuzz(const FuzzOptions& options) {
  CampaignOptions campaign;
  campaign.seed = options.seed;
  campaign.cases = options.cases;
  const ShardOption shard = shard_option(options.shard, "--shard");
  campaign.shard = {shard.k - 1, shard.n};
  campaign.triangles = options.triangles;
  try {
    campaign.runs = parse_campaign_runs(options.methods);
  } catch (const std::invalid_argument& e) {
    throw CLI::ValidationError("--methods", e.what());
  }
  campaign.max_shrunk_per_run = options.max_reproducers;
  campaign.shrink_findings = options.shrink_findings;
  const unsigned threads =
      options.threads > 0 ? options.threads : static_cast<unsigned>(tbb::info::default_concurrency());
  const tbb::global_control parallelism(tbb::global_control::max_allowed_parallelism, threads);

  // The GL part's options are checked, and its context made current on this thread, before
  // the exact part runs: a machine without EGL fails at once (exit 2, the driver's message).
  GlCampaignOptions gl;
  std::optional<gpu::EglContext> context;
  if (options.gl) {
    gl.seed = options.seed;
    gl.cases = options.cases;
    gl.shard = campaign.shard;
    gl.triangles = options.triangles;
    gl.methods = shadow_methods_option(options.gl_methods, "--gl-methods");
    Camera size;
    apply_image_size(options.gl_size, size, "--gl-size");
    gl.width = size.width;
    gl.height = size.height;
    gl.scenes = options.gl_scenes == "hard" ? GlSceneSource::hard : GlSceneSource::soups;  // CLI11 checked it
    gl.max_shrunk_per_method = options.max_reproducers;
    gl.sign = *gpu::parse_sign_mode(options.sign);  // CLI11 checked the name
    context.emplace(gpu::open_gl_context("fuzz --gl", options.device));
  }

  const CampaignResult result = run_with_progress(campaign);
  print_summary(options, campaign, result, threads);

  // Then the GL methods, case after case on this one thread (its context).
  std::optional<GlCampaignResult> gl_result;
  if (options.gl) {
    std::atomic<std::uint64_t> done{0};
    gl.progress = &done;
    {
      const ProgressLine progress("fuzz --gl", shard_case_count(gl.cases, gl.shard), done);
      gl_result = run_gl_campaign(gl);
    }
    print_gl_summary(gl, *gl_result, *context);
  }

  std::vector<WrittenReproducer> written;
  for (const ShrunkFailure& shrunk : result.shrunk) written.push_back(write_reproducer(options, campaign, shrunk));
  for (const WrittenReproducer& w : written) {
    fmt::print("{} {} case {}: {}, shrunk {} -> {} triangles ({}), replays with\n  {}\n",
               w.failure == "closure" ? "OPEN CHAIN" : "WRONG COUNTS", w.run, w.case_index, w.failure,
               w.original_triangles, w.triangles, w.replayed ? "replayed bit for bit" : "REPLAY DID NOT REPRODUCE",
               w.command);
  }
  if (!result.shrunk.empty())
    fmt::print("shrunk {} failures in {:.2f} s; reproducers in {}\n", result.shrunk.size(), result.shrink_seconds,
               options.out_dir);
  std::vector<GlReproducer> gl_written;
  if (gl_result) {
    for (const ShrunkGlFailure& shrunk : gl_result->shrunk)
      gl_written.push_back(write_gl_reproducer(options.out_dir, gl, shrunk));
    for (const GlReproducer& w : gl_written)
      fmt::print("{} {} case {}: {}, shrunk {} -> {} triangles ({}), replays with\n  {}\n",
                 w.failure == "closure" ? "OPEN VOLUME" : "HARD ERRORS", w.method, w.case_index, w.failure,
                 w.original_triangles, w.triangles, w.replayed ? "diff fails the same way" : "REPLAY DID NOT REPRODUCE",
                 w.command);
    if (!gl_result->shrunk.empty())
      fmt::print("shrunk {} GL failures in {:.2f} s; reproducers in {}\n", gl_result->shrunk.size(),
                 gl_result->shrink_seconds, options.out_dir);
  }

  bool must_not_fail_failed = false;
  for (std::size_t r = 0; r < campaign.runs.size(); ++r)
    if (must_not_fail(campaign.runs[r]) && result.runs[r].failures > 0) must_not_fail_failed = true;
  if (gl_result)
    for (std::size_t m = 0; m < gl.methods.size(); ++m)
      if (robust(gl.methods[m]) && gl_result->methods[m].failures > 0) must_not_fail_failed = true;

  if (!options.json_file.empty()) {
    nlohmann::json methods = nlohmann::json::object(), runs = nlohmann::json::array();
    for (std::size_t r = 0; r < campaign.runs.size(); ++r) {
      methods[campaign_run_name(campaign.runs[r])] = tally_json(campaign.runs[r], result.runs[r]);
      runs.push_back(campaign_run_name(campaign.runs[r]));
    }
    nlohmann::json families = nlohmann::json::object(), placements = nlohmann::json::object();
    for (std::size_t i = 0; i < result.cases_by_family.size(); ++i)
      families[std::string(family_name(static_cast<SoupFamily>(i)))] = result.cases_by_family[i];
    for (std::size_t i = 0; i < result.cases_by_placement.size(); ++i)
      placements[std::string(placement_name(static_cast<LightPlacement>(i)))] = result.cases_by_placement[i];
    nlohmann::json reproducers = nlohmann::json::array();
    for (const WrittenReproducer& w : written)
      reproducers.push_back({{"run", w.run},
                             {"case", w.case_index},
                             {"failure", w.failure},
                             {"original_triangles", w.original_triangles},
                             {"triangles", w.triangles},
                             {"file", w.json.string()},
                             {"command", w.command},
                             {"replayed", w.replayed}});
    for (const GlReproducer& w : gl_written)
      reproducers.push_back({{"run", w.method},
                             {"case", w.case_index},
                             {"failure", w.failure},
                             {"original_triangles", w.original_triangles},
                             {"triangles", w.triangles},
                             {"file", w.json.string()},
                             {"command", w.command},
                             {"replayed", w.replayed}});
    nlohmann::json gl_json = nullptr;
    if (gl_result) {
      nlohmann::json names = nlohmann::json::array();
      for (std::size_t m = 0; m < gl.methods.size(); ++m) {
        methods[gl_run_name(gl.methods[m])] = gl_tally_json(gl.methods[m], gl_result->methods[m]);
        names.push_back(gl_run_name(gl.methods[m]));
      }
      nlohmann::json parts = nlohmann::json::object();
      for (std::size_t i = 0; i < gl_result->cases_by_part.size(); ++i)
        parts[std::string(hard_part_name(static_cast<HardPart>(i)))] = gl_result->cases_by_part[i];
      gl_json = {{"renderer", context->renderer()},
                 {"device", context->device()},
                 {"scenes", gl_scene_source_name(gl.scenes)},
                 {"parts", parts},
                 {"light_on_plane", gl_result->cases_light_on_plane},
                 {"edge_on", gl_result->cases_edge_on},
                 {"size", {gl.width, gl.height}},
                 {"sign", gpu::sign_mode_name(gl.sign)},
                 {"methods", names},
                 {"cases", gl_result->cases},
                 {"seconds", gl_result->seconds},
                 {"cases_per_second", gl_result->seconds > 0.0
                                          ? static_cast<double>(gl_result->cases) / gl_result->seconds
                                          : 0.0},
                 {"exact_seconds", gl_result->exact_seconds},
                 {"shrink_seconds", gl_result->shrink_seconds}};
    }
    write_json_file(
        options.json_file,
        {{"schema", "shadowcert-fuzz/1"},
         {"seed", campaign.seed},
         {"case_count", campaign.cases},
         {"shard", {{"index", campaign.shard.index + 1}, {"count", campaign.shard.count}}},
         {"cases", result.cases},
         {"triangles", campaign.triangles},
         {"runs", runs},
         {"max_reproducers", options.max_reproducers},
         {"shrink_findings", options.shrink_findings},
         {"threads", threads},
         {"seconds", result.seconds},
         {"cases_per_second", result.seconds > 0.0 ? static_cast<double>(result.cases) / result.seconds : 0.0},
         {"shrink_seconds", result.shrink_seconds},
         {"samples", result.samples},
         {"redrawn_samples", result.redrawn},
         {"lost_samples", result.lost},
         {"families", families},
         {"placements", placements},
         {"methods", methods},
         {"must_not_fail_failed", must_not_fail_failed},
         {"gl", gl_json},
         {"reproducers", reproducers}});
  }
  if (must_not_fail_failed) {
    fmt::print(stderr,
               "shadowcert: a method that must not fail (exact, peciva, refedge; with --gl cpu, cs, gs, ts, pertri) "
               "failed: see the reproducers\n");
    return kExitCheckFailed;
  }
  return kExitOk;
}

}  // namespace

void add_fuzz_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<FuzzOptions>();
  CLI::App* cmd = app.add_subcommand(
      "fuzz", "Random soups and adversarial lights: certify every method, shrink failures (docs/campaign.md)");
  cmd->add_option("--seed", options->seed, "Campaign seed: case i is a function of (seed, i) alone")
      ->capture_default_str();
  cmd->add_option("--cases", options->cases, "Number of cases")->capture_default_str()->check(CLI::PositiveNumber);
  cmd->add_option("--shard", options->shard,
                  "K/N: only the cases i with i % N == K - 1 (1 <= K <= N); the shards' --json files merge into the "
                  "whole run's with shadowcert merge (docs/batch-runs.md)");
  cmd->add_option("--triangles", options->triangles, "Triangles per soup")
      ->capture_default_str()
      ->check(CLI::Range(std::uint32_t{1}, kMaxTriangles));
  cmd->add_option("--methods", options->methods,
                  "Comma-separated runs: exact, kim, peciva, refedge (both precisions), a run such as "
                  "refedge-float, or all")
      ->capture_default_str();
  CLI::Option* gl_flag = cmd->add_flag("--gl", options->gl,
                "Also render every case with the GL methods (one EGL context, after the exact part): closure of "
                "each captured volume and hard errors against the exact image");
  cmd->add_option("--gl-methods", options->gl_methods,
                  "With --gl: comma-separated GL methods (cpu, cs, gs, ts, pertri; shadowmap as a baseline)")
      ->capture_default_str()
      ->needs(gl_flag);
  cmd->add_option("--gl-size", options->gl_size, "With --gl: image size WxH")->capture_default_str()->needs(gl_flag);
  cmd->add_option("--gl-scenes", options->gl_scenes,
                  "With --gl: what each case renders: its random soup in the campaign view (soups) or a hard-soup "
                  "scene, several hard soups over a floor with lights close to them (hard)")
      ->check(CLI::IsMember({"soups", "hard"}))
      ->capture_default_str()
      ->needs(gl_flag);
  cmd->add_option("--sign", options->sign,
                  "With --gl: cs, gs, ts, pertri take exact signs of their float inputs (exact) or the float "
                  "formula's (float, Milet 2014 refedge)")
      ->check(CLI::IsMember({"exact", "float"}))
      ->capture_default_str()
      ->needs(gl_flag);
  cmd->add_option("--device", options->device, "With --gl: EGL device N (default: a hardware device, else llvmpipe)")
      ->needs(gl_flag);
  cmd->add_option("--out", options->out_dir, "Folder for shrunk reproducers (written only on failures)")
      ->capture_default_str();
  cmd->add_option("--json", options->json_file, "Write the summary as a JSON object to FILE");
  cmd->add_option("--threads", options->threads, "Worker threads (0: every core)")->capture_default_str();
  cmd->add_option("--max-reproducers", options->max_reproducers, "Failing cases shrunk and written per run")
      ->capture_default_str();
  cmd->add_flag("--shrink-findings", options->shrink_findings,
                "Also shrink and write failures of runs allowed to fail (kim), as findings");
  cmd->callback([options, &exit_code] { exit_code = run_fuzz(*options); });
}

}  // namespace shadowcert::cli
