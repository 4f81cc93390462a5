#include "cli/certify_command.h"

#include <fmt/core.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/exit_code.h"
#include "cli/silhouette_output.h"
#include "cli/wall_clock.h"
#include "exact/volume_closure.h"
#include "gpu/egl_context.h"
#include "pipeline/method_certificate.h"
#include "pipeline/silhouette_volumes.h"
#include "io/output_file.h"
#include "io/scene_input.h"
#include "io/soup_file.h"
#include "core/input_error.h"
#include "io/volume_file.h"
#include "exact/closure_certificate.h"
#include "exact/count_certificate.h"
#include "exact/edge_multiplicity.h"
#include "scene/edge_table.h"
#include "scene/merged_soup.h"
#include "exact/shadow_volume_chain.h"
#include "scene/canonical_soup.h"
#include "io/point_file.h"

namespace shadowcert::cli {
namespace {

// Far vertices of --volume-out are pushed this many scene diagonals away: far enough to
// read as infinite in a viewer, near enough to stay well inside float range.
constexpr double kFarDistanceInDiagonals = 10.0;

struct CertifyOptions {
  std::string input;
  std::vector<double> light;  // empty: the scene's first light
  std::string method = "all";
  std::string precision = "float";
  std::uint64_t samples = 2000;
  std::uint64_t seed = 1;
  std::string points_file;
  std::string volume_out;
  std::string volume;  // a captured volume (.vol) to certify alone
  std::string json_file;
  SilhouetteOptions silhouette;  // --method discrete|accurate|smooth: --epsilon, --crease-angle
};


Light chosen_light(const CertifyOptions& options, const Scene& scene) {
  if (options.light.empty()) {
    if (scene.lights.empty()) throw InputError(options.input, "the scene has no light; pass --light X,Y,Z,W");
    return scene.lights.front();
  }
  if (options.light.size() != 4) throw CLI::ValidationError("--light", "expects four numbers X,Y,Z,W");
  Light light;
  for (int k = 0; k < 4; ++k) {
    if (!std::isfinite(options.light[k])) throw CLI::ValidationError("--light", "coordinates must be finite");
    light.position[k] = options.light[k];
  }
  if (light.position[3] != 0.0 && light.position[3] != 1.0)
    throw CLI::ValidationError("--light", "W must be 1 (point light) or 0 (directional light)");
  if (light.directional() && light.position[0] == 0.0 && light.position[1] == 0.0 && light.position[2] == 0.0)
    throw CLI::ValidationError("--light", "a directional light needs a nonzero direction");
  return light;
}

// discrete, accurate, smooth, smooth-gpu: the smooth-silhouette method of that name, else nullopt.
std::optional<gpu::ShadowMethod> silhouette_method(const std::string& name) {
  for (gpu::ShadowMethod m : gpu::kSilhouetteMethods)
    if (gpu::shadow_method_name(m) == name) return m;
  return std::nullopt;
}

// certify --method discrete|accurate|smooth|smooth-gpu: every light's volume built as render draws it
// (pipeline/silhouette_volumes.h), in world space, certified closed exactly
// (exact/volume_closure.h); how each mesh cast. An open volume is a bug: exit 1.
int run_certify_silhouette(const CertifyOptions& options, const Scene& scene, gpu::ShadowMethod method) {
  std::vector<Light> lights;
  if (options.light.empty()) lights = scene.lights;
  else lights.push_back(chosen_light(options, scene));
  if (lights.empty()) throw InputError(options.input, "the scene has no light; pass --light X,Y,Z,W");
  const auto start = Clock::now();
  SilhouetteVolumes volumes = silhouette_volumes(scene.meshes, lights, method, options.silhouette);
  // smooth-gpu: the GPU builds the smooth casters' part, read back as drawn.
  std::optional<gpu::EglContext> context;
  if (method == gpu::ShadowMethod::smooth_gpu) {
    context.emplace(gpu::open_gl_context("certify", std::nullopt));
    capture_gpu_volumes(volumes, lights);
  }
  const double build_seconds = seconds_since(start);
  fmt::print("{}: {} mesh(es), {} light(s), {} (built in {:.3f} s)\n", options.input, scene.meshes.size(), lights.size(),
             gpu::shadow_method_name(method), build_seconds);
  print_silhouette_casters(volumes);
  bool all_closed = true;
  nlohmann::json per_light = nlohmann::json::array();
  for (std::size_t k = 0; k < lights.size(); ++k) {
    const VolumeClosure closure = certify_volume_closure(volumes.per_light[k]);
    all_closed = all_closed && closure.certificate.closed;
    fmt::print("  light {}: {} triangles, closure {} ({} unbalanced edges)\n", k, volumes.per_light[k].triangles.size(),
               closure.certificate.closed ? "certified" : "FAILED", closure.certificate.unbalanced.size());
    per_light.push_back({{"light", lights[k].position},
                         {"triangles", volumes.per_light[k].triangles.size()},
                         {"closed", closure.certificate.closed},
                         {"unbalanced_edges", closure.certificate.unbalanced.size()}});
  }
  if (!options.json_file.empty())
    write_json_file(options.json_file, {{"input", options.input},
                                        {"method", gpu::shadow_method_name(method)},
                                        {"epsilon", options.silhouette.epsilon},
                                        {"crease_angle", options.silhouette.crease_angle_degrees},
                                        {"build_seconds", build_seconds},
                                        {"casters", silhouette_casters_json(volumes)},
                                        {"lights", per_light},
                                        {"closed", all_closed}});
  return all_closed ? kExitOk : kExitCheckFailed;
}

std::vector<MultiplicityMethod> chosen_methods(const std::string& name) {
  if (name == "all")
    return {MultiplicityMethod::exact, MultiplicityMethod::kim, MultiplicityMethod::peciva,
            MultiplicityMethod::refedge};
  try {
    return {parse_method(name)};
  } catch (const std::invalid_argument&) {
    throw CLI::ValidationError("--method", "unknown method '" + name +
                                               "' (exact, kim, peciva, refedge, all, discrete, accurate, smooth, smooth-gpu)");
  }
}

double scene_diagonal(const Soup& soup) {
  Vec3 lo = soup.vertices.front(), hi = lo;
  for (const Vec3& p : soup.vertices)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  return std::hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
}

std::filesystem::path volume_path(const std::string& base, MultiplicityMethod method, bool several) {
  if (!several) return base;
  std::filesystem::path p(base);
  return p.parent_path() / (p.stem().string() + "_" + std::string(method_name(method)) + p.extension().string());
}

// One method's certificates (pipeline/method_certificate.h); with --volume-out, its chain drawn
// to a file as well.
MethodCertificate certify_and_draw(MultiplicityMethod method, Precision precision, const Soup& soup,
                                   const EdgeTable& table, const Light& light, const CountSampling& sampling,
                                   const CertifyOptions& options, bool several_methods) {
  ShadowVolumeChain chain;
  MethodCertificate c = certify_method(method, precision, soup, table, light, sampling, &chain);
  if (!options.volume_out.empty()) {
    const std::filesystem::path file = volume_path(options.volume_out, method, several_methods);
    create_parent_directories(file);
    write_soup(file, chain_picture(chain, soup, light,
                               kFarDistanceInDiagonals * std::max(scene_diagonal(soup), 1.0)));
  }
  return c;
}

void print_report(const MethodCertificate& r) {
  fmt::print("{}\n", r.name);
  fmt::print("  closed                 {}", r.closure.closed ? "yes" : "NO");
  if (!r.closure.closed) fmt::print(" ({} unbalanced edges)", r.closure.unbalanced.size());
  fmt::print("\n  count checks           {} passed, {} failed ({} redrawn, {} skipped)\n",
             r.counts.checks - r.counts.failures, r.counts.failures, r.counts.redrawn, r.counts.skipped);
  fmt::print("  silhouette edges       {}\n", r.silhouette_edges);
  fmt::print("  max |m|                {}\n", r.max_multiplicity);
  fmt::print("  |m| histogram         ");
  for (const auto& [magnitude, edges] : r.histogram) fmt::print(" {}:{}", magnitude, edges);
  fmt::print("\n  triangles with s = 0   {}\n", r.zero_facing_triangles);
  fmt::print("  seconds                multiplicities {:.3f}, chain {:.3f}, closure {:.3f}, counts {:.3f}\n",
             r.multiplicity_seconds, r.chain_seconds, r.closure_seconds, r.counts.seconds);
}

// How many unbalanced edges are printed (and put in the JSON) with their coordinates.
constexpr std::size_t kShownUnbalanced = 8;

// certify --volume: closure of what a method drew (render --capture). An open volume from a
// robust method is the bug this exists to catch, hence exit 1.
int run_certify_volume(const CertifyOptions& options) {
  const auto start = Clock::now();
  const HomogeneousMesh volume = read_volume_file(options.volume);
  const VolumeClosure result = certify_volume_closure(volume);
  const double seconds = seconds_since(start);
  const ClosureCertificate& c = result.certificate;
  fmt::print("{}: {} triangles, {} welded vertices\n", options.volume, result.welded.triangles.size(),
             result.welded.vertices.size());
  fmt::print("  closed                 {}", c.closed ? "yes" : "NO");
  if (!c.closed) fmt::print(" ({} unbalanced edges)", c.unbalanced.size());
  fmt::print("\n");
  nlohmann::json first = nlohmann::json::array();
  for (std::size_t i = 0; i < c.unbalanced.size() && i < kShownUnbalanced; ++i) {
    const UnbalancedEdge& e = c.unbalanced[i];
    const auto& a = result.welded.vertices[e.from];
    const auto& b = result.welded.vertices[e.to];
    fmt::print("  unbalanced edge ({}, {}, {}, {}) -> ({}, {}, {}, {}), excess {}\n", a[0], a[1], a[2], a[3], b[0],
               b[1], b[2], b[3], e.excess);
    first.push_back({{"from", a}, {"to", b}, {"excess", e.excess}});
  }
  if (!options.json_file.empty())
    write_json_file(options.json_file, {{"volume", options.volume},
                                        {"closed", c.closed},
                                        {"unbalanced_edges", c.unbalanced.size()},
                                        {"first_unbalanced", first},
                                        {"triangles", result.welded.triangles.size()},
                                        {"vertices", result.welded.vertices.size()},
                                        {"seconds", seconds}});
  return c.closed ? kExitOk : kExitCheckFailed;
}

int run_certify(const CertifyOptions& options) {
  if (!options.volume.empty()) {
    if (!options.input.empty())
      throw CLI::ValidationError("--volume", "certifies a captured volume alone; drop the MESH|SCENE argument");
    return run_certify_volume(options);
  }
  if (options.input.empty()) throw CLI::ValidationError("input", "give a MESH|SCENE file, or --volume FILE");
  const auto start = Clock::now();
  const Scene scene = load_scene_or_mesh(options.input);
  if (const std::optional<gpu::ShadowMethod> silhouette = silhouette_method(options.method))
    return run_certify_silhouette(options, scene, *silhouette);
  const Light light = chosen_light(options, scene);
  const std::vector<MultiplicityMethod> methods = chosen_methods(options.method);
  if (options.precision != "float" && options.precision != "double")
    throw CLI::ValidationError("--precision", "expects float or double");
  const Precision precision = options.precision == "float" ? Precision::float32 : Precision::float64;

  // The shadow volumes' input: the casting meshes only (a mesh with "casts": false is in none).
  const Soup input = merged_casters(scene);
  if (input.triangles.empty()) throw InputError(options.input, "no casting triangle to certify");
  const double load_seconds = seconds_since(start);

  auto stage = Clock::now();
  const CanonicalSoup canonical = canonical_soup(input);
  const double canonical_seconds = seconds_since(stage);
  stage = Clock::now();
  const EdgeTable table = build_edge_table(canonical.soup);
  const double table_seconds = seconds_since(stage);

  CountSampling sampling;
  sampling.in_box = options.samples / 2;
  sampling.on_triangles = options.samples - sampling.in_box;
  sampling.seed = options.seed;
  if (!options.points_file.empty()) sampling.user_points = read_point_file(options.points_file);

  fmt::print("{}: {} triangles, {} welded vertices, {} edges; light ({}, {}, {}, {})\n", options.input,
             input.triangles.size(), canonical.soup.vertices.size(), table.size(), light.position[0],
             light.position[1], light.position[2], light.position[3]);
  fmt::print("seconds: load {:.3f}, weld+order {:.3f}, edge table {:.3f}\n", load_seconds, canonical_seconds,
             table_seconds);

  nlohmann::json json_methods = nlohmann::json::object();
  bool exact_failed = false;
  for (MultiplicityMethod method : methods) {
    const MethodCertificate report = certify_and_draw(method, precision, canonical.soup, table, light, sampling,
                                                      options, methods.size() > 1);
    print_report(report);
    json_methods[report.name] = method_certificate_json(report);
    if (method == MultiplicityMethod::exact && !report.passed()) exact_failed = true;
  }

  if (!options.json_file.empty()) {
    const nlohmann::json report = {
        {"input", options.input},
        {"triangles", input.triangles.size()},
        {"welded_vertices", canonical.soup.vertices.size()},
        {"edges", table.size()},
        {"light", light.position},
        {"precision", options.precision},
        {"seed", options.seed},
        {"samples", options.samples},
        {"user_points", sampling.user_points.size()},
        {"stage_seconds", {{"load", load_seconds}, {"weld_and_order", canonical_seconds}, {"edge_table", table_seconds}}},
        {"methods", json_methods}};
    write_json_file(options.json_file, report);
  }
  if (exact_failed) {
    fmt::print(stderr, "shadowcert: the exact method failed a certificate: this is a bug, please report it\n");
    return kExitCheckFailed;
  }
  return kExitOk;
}

}  // namespace

void add_certify_command(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<CertifyOptions>();
  CLI::App* cmd = app.add_subcommand("certify", "Exact multiplicities and shadow-volume certificates (docs/definitions.md#certificates)");
  cmd->add_option("input", options->input, "Mesh file (.obj .off .ply .stl) or scene (.json); not with --volume");
  cmd->add_option("--light", options->light, "Light X,Y,Z,W (W = 1 point, W = 0 directional); default: the scene's first")
      ->delimiter(',')
      ->expected(4);
  cmd->add_option("--method", options->method,
                  "exact, kim, peciva, refedge or all (multiplicities and their certificates), or discrete, accurate, "
                  "smooth, smooth-gpu (the smooth-silhouette volume of every light, certified closed; smooth-gpu's "
                  "built on the GPU through EGL and read back; docs/smooth-silhouettes.md)")
      ->capture_default_str();
  add_silhouette_options(*cmd, options->silhouette);
  cmd->add_option("--precision", options->precision, "Arithmetic of the float methods: float or double")
      ->capture_default_str();
  cmd->add_option("--samples", options->samples, "Random count-check samples (half in the box, half on triangles)")
      ->capture_default_str();
  cmd->add_option("--seed", options->seed, "Seed of the random samples")->capture_default_str();
  cmd->add_option("--points", options->points_file, "Extra sample points, one \"x y z\" per line");
  cmd->add_option("--volume-out", options->volume_out,
                  "Write the chain (.off .obj .ply; far vertices pushed to a finite distance); with several "
                  "methods, one file per method named FILE_method.ext");
  cmd->add_option("--volume", options->volume,
                  "Certify only the closure of a captured volume (.vol from render --capture); exit 1 when open");
  cmd->add_option("--json", options->json_file, "Write the certificates as a JSON object to FILE");
  cmd->callback([options, &exit_code] { exit_code = run_certify(*options); });
}

}  // namespace shadowcert::cli
