#include "campaign/reproducer.h"

#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "core/input_error.h"
#include "exact/closure_certificate.h"
#include "exact/count_certificate.h"
#include "campaign/campaign_run.h"
#include "exact/shadow_volume_chain.h"
#include "io/soup_file.h"
#include "scene/canonical_soup.h"
#include "scene/edge_table.h"
#include "scene/json_field.h"
#include "scene/json_text.h"
#include "io/point_file.h"

namespace shadowcert {
namespace {

namespace fs = std::filesystem;

// {:.17g}: 17 significant digits read back bitwise equal (what write_soup uses too).
std::string exact_number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", x);
  return text;
}

void write_text(const fs::path& file, const std::string& text) {
  std::ofstream out(file);
  if (!out) throw std::runtime_error("write_reproducer: cannot open '" + file.string() + "' for writing");
  out << text;
  out.close();
  if (!out) throw std::runtime_error("write_reproducer: writing '" + file.string() + "' failed");
}

std::string read_text(const fs::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError(file.string(), "cannot open the reproducer");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

Precision parse_precision(const JsonField& field) {
  const std::string name = field.string();
  if (name == "float") return Precision::float32;
  if (name == "double") return Precision::float64;
  field.fail("expected \"float\" or \"double\", got \"" + name + "\"");
}

bool counts_failure(const CampaignReproducer& r) { return r.failure == "counts"; }

}  // namespace

std::string certify_command(const CampaignReproducer& r, const fs::path& mesh, const fs::path& points) {
  const auto& l = r.light.position;
  std::string command = "shadowcert certify " + mesh.string() + " --light=" + exact_number(l[0]) + "," +
                        exact_number(l[1]) + "," + exact_number(l[2]) + "," + exact_number(l[3]) + " --method " +
                        std::string(method_name(r.method)) + " --precision " + std::string(precision_name(r.precision));
  if (counts_failure(r)) command += " --samples 0 --points " + points.string();
  return command;
}

fs::path write_reproducer(const fs::path& dir, const std::string& name, const CampaignReproducer& r) {
  std::error_code error;
  fs::create_directories(dir, error);
  if (error)
    throw std::runtime_error("write_reproducer: cannot create '" + dir.string() + "': " + error.message());
  const fs::path mesh = dir / (name + ".off"), points = dir / (name + ".points"), json = dir / (name + ".json");
  write_soup(mesh, r.soup);
  if (counts_failure(r)) {
    std::string text;
    for (const Vec3& p : r.points)
      text += exact_number(p[0]) + " " + exact_number(p[1]) + " " + exact_number(p[2]) + "\n";
    write_text(points, text);
  }
  // The light goes in as text too: nlohmann prints doubles round-trip exactly, but a reader
  // can then copy the very numbers of the command line.
  nlohmann::json j = {{"mesh", mesh.filename().string()},
                      {"light", r.light.position},
                      {"method", std::string(method_name(r.method))},
                      {"precision", std::string(precision_name(r.precision))},
                      {"failure", r.failure},
                      {"status", r.status},
                      {"seed", r.seed},
                      {"case", r.case_index},
                      {"family", r.family},
                      {"placement", r.placement},
                      {"original_triangles", r.original_triangles},
                      {"triangles", r.soup.triangles.size()},
                      {"command", certify_command(r, mesh.filename(), points.filename())}};
  if (counts_failure(r)) j["points"] = points.filename().string();
  write_text(json, j.dump(2) + "\n");
  return json;
}

CampaignReproducer read_reproducer(const fs::path& json) {
  const std::string name = json.string();
  const nlohmann::json document = parse_json_text(read_text(json), name);
  const JsonField root(document, name);
  root.require_keys_within({"mesh", "light", "method", "precision", "failure", "status", "seed", "case", "family",
                            "placement", "original_triangles", "triangles", "command", "points"});
  auto required = [&root](std::string_view key) {
    std::optional<JsonField> field = root.member(key);
    if (!field) root.fail("missing key \"" + std::string(key) + "\"");
    return *field;
  };
  CampaignReproducer r;
  const JsonField light = required("light");
  if (light.array_size() != 4) light.fail("expected four numbers x, y, z, w");
  for (std::size_t k = 0; k < 4; ++k) r.light.position[k] = light.element(k).number();
  if (r.light.position[3] != 0.0 && r.light.position[3] != 1.0) light.fail("w must be 0 or 1");
  const JsonField method = required("method");
  try {
    r.method = parse_method(method.string());
  } catch (const std::invalid_argument& e) {
    method.fail(e.what());
  }
  r.precision = parse_precision(required("precision"));
  const JsonField failure = required("failure");
  r.failure = failure.string();
  if (r.failure != "closure" && r.failure != "counts") failure.fail("expected \"closure\" or \"counts\"");
  const JsonField status = required("status");
  r.status = status.string();
  if (r.status != "open" && r.status != "fixed" && r.status != "finding")
    status.fail("expected \"open\", \"fixed\" or \"finding\"");
  r.seed = unsigned_or(root, "seed", UINT64_MAX, 0);
  r.case_index = unsigned_or(root, "case", UINT64_MAX, 0);
  if (const std::optional<JsonField> f = root.member("family")) r.family = f->string();
  if (const std::optional<JsonField> f = root.member("placement")) r.placement = f->string();
  r.original_triangles = unsigned_or(root, "original_triangles", UINT64_MAX, 0);
  const fs::path folder = json.parent_path();
  r.soup = read_soup(folder / required("mesh").string());
  if (counts_failure(r)) {
    r.points = read_point_file(folder / required("points").string());
    if (r.points.size() != 2) throw InputError(name, "a count failure needs the two points of its failing pair");
  }
  return r;
}

ReproducerReplay replay_reproducer(const CampaignReproducer& r) {
  // cli/certify_command.cpp, step for step: canonical soup, edge table, the method, the chain,
  // closure; counts with no random sample, only the recorded pair.
  const Soup canonical = canonical_soup(r.soup).soup;
  const EdgeTable table = build_edge_table(canonical);
  const EdgeMultiplicities m = edge_multiplicities(r.method, canonical, table, r.light, r.precision);
  const ShadowVolumeChain chain = assemble_chain(canonical, table, m, r.light);
  ReproducerReplay replay;
  replay.closed = certify_closure(chain).closed;
  if (!r.points.empty()) {
    CountSampling sampling;
    sampling.in_box = 0;
    sampling.on_triangles = 0;
    sampling.user_points = r.points;
    const CountCertificate counts = certify_counts(canonical, r.light, chain, sampling);
    replay.count_checks = counts.checks;
    replay.count_failures = counts.failures;
  }
  replay.reproduces = counts_failure(r) ? replay.count_failures > 0 : !replay.closed;
  return replay;
}

}  // namespace shadowcert
