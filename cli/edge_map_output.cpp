#include "cli/edge_map_output.h"

#include <fmt/core.h>

#include <algorithm>

#include "gpu/png_image.h"
#include "pipeline/edge_map_pictures.h"

namespace shadowcert::cli {
namespace {

std::uint64_t count(const std::vector<EdgeTruth>& truth, EdgeTruth value) {
  return static_cast<std::uint64_t>(std::count(truth.begin(), truth.end(), value));
}

// The thresholds the row's class read: {"profile": T}, {"inner": T}, or both for any.
nlohmann::json thresholds_json(const EdgeScoreRow& row) {
  nlohmann::json j = nlohmann::json::object();
  if (row.edge_class != EdgeClass::inner) j["profile"] = row.thresholds.profile;
  if (row.edge_class != EdgeClass::profile) j["inner"] = row.thresholds.inner;
  return j;
}

nlohmann::json counts_json(const EdgeMatchCounts& m) {
  return {{"precision", m.precision()},      {"recall", m.recall()},   {"f1", m.f1()},
          {"detections", m.detections},      {"true_detections", m.true_detections},
          {"truth", m.truth},                {"found", m.found},       {"grazing_false", m.grazing_false},
          {"grazing_pixels", m.grazing_pixels}};
}

}  // namespace

void print_edge_maps(const EdgeMapComparison& c) {
  const EdgeGroundTruth& t = c.truth;
  fmt::print("  edge maps against the exact ground truth ({:.2f} s: {} profile, {} inner truth pixels, {} excluded; "
             "reported, never a failure):\n",
             t.stats.seconds, count(t.profile, EdgeTruth::edge), count(t.inner, EdgeTruth::edge),
             count(t.profile, EdgeTruth::excluded) + count(t.inner, EdgeTruth::excluded));
  std::string header = fmt::format("  {:<9} {:<8} {:>18}", "filter", "class", "default thresholds");
  for (const EdgeTolerance& tolerance : c.tolerances) header += fmt::format(" {:>17}", tolerance.name() + " P/R/F1");
  fmt::print("{} {:>14}\n", header, "grazing false");
  for (const EdgeScoreRow& row : edge_score_rows(c)) {
    std::string line = fmt::format("  {:<9} {:<8} {:>18}", gpu::edge_filter_name(row.filter),
                                   edge_class_name(row.edge_class),
                                   edge_class_thresholds_text(row.edge_class, row.thresholds));
    for (const EdgeMatchCounts& m : row.counts)
      line += fmt::format(" {:>17}", fmt::format("{:.2f}/{:.2f}/{:.2f}", m.precision(), m.recall(), m.f1()));
    const EdgeMatchCounts& first = row.counts.front();
    fmt::print("{} {:>14}\n", line, fmt::format("{}/{}", first.grazing_false, first.grazing_pixels));
  }
}

nlohmann::json edge_maps_json(const EdgeMapComparison& c, double crease_degrees, double grazing_degrees) {
  const EdgeGroundTruth& t = c.truth;
  nlohmann::json tolerances = nlohmann::json::array();
  for (const EdgeTolerance& tolerance : c.tolerances) tolerances.push_back(tolerance.name());
  nlohmann::json filters = nlohmann::json::object();
  for (const EdgeScoreRow& row : edge_score_rows(c)) {
    nlohmann::json j{{"thresholds", thresholds_json(row)}};
    for (std::size_t k = 0; k < row.counts.size(); ++k) j[c.tolerances[k].name()] = counts_json(row.counts[k]);
    filters[std::string(gpu::edge_filter_name(row.filter))][std::string(edge_class_name(row.edge_class))] = j;
  }
  return {{"crease_angle", crease_degrees},
          {"grazing_angle", grazing_degrees},
          {"truth",
           {{"profile_pixels", count(t.profile, EdgeTruth::edge)},
            {"inner_pixels", count(t.inner, EdgeTruth::edge)},
            {"excluded_pixels", count(t.profile, EdgeTruth::excluded) + count(t.inner, EdgeTruth::excluded)},
            {"grazing_pixels", std::count(t.grazing.begin(), t.grazing.end(), std::uint8_t{1})},
            {"profile_edges", t.stats.profile_edges},
            {"inner_edges", t.stats.inner_edges},
            {"visible_profile_edges", t.stats.visible_profile_edges},
            {"visible_inner_edges", t.stats.visible_inner_edges},
            {"seconds", t.stats.seconds}}},
          {"tolerances", tolerances},
          {"filters", filters}};
}

void write_edge_map_pictures(const std::filesystem::path& dir, const EdgeMapComparison& c) {
  for (const NamedEdgePicture& p : edge_map_pictures(c)) gpu::write_png((dir / (p.name + ".png")).string(), p.image);
}

std::vector<std::pair<std::string, std::string>> edge_map_facts(const EdgeMapComparison& c) {
  std::vector<std::pair<std::string, std::string>> facts;
  facts.emplace_back("edge ground truth",
                     fmt::format("{:.2f} s; {} profile and {} inner pixels (verdicts: green true, red false, magenta "
                                 "false on a grazing surface, blue missed, pale green found by a neighbour)",
                                 c.truth.stats.seconds, count(c.truth.profile, EdgeTruth::edge),
                                 count(c.truth.inner, EdgeTruth::edge)));
  for (const EdgeScoreRow& row : edge_score_rows(c)) {
    std::string text = fmt::format("default thresholds {}", edge_class_thresholds_text(row.edge_class, row.thresholds));
    for (std::size_t k = 0; k < row.counts.size(); ++k)
      text += fmt::format("; {} P {:.3f} R {:.3f} F1 {:.3f}", c.tolerances[k].name(), row.counts[k].precision(),
                          row.counts[k].recall(), row.counts[k].f1());
    facts.emplace_back(fmt::format("edges, {} {}", gpu::edge_filter_name(row.filter), edge_class_name(row.edge_class)),
                       text);
  }
  return facts;
}

std::vector<ReportImage> edge_map_report_images(const EdgeMapComparison& c) {
  std::vector<ReportImage> images;
  for (const NamedEdgePicture& p : edge_map_pictures(c)) images.push_back({p.name, gpu::encode_png(p.image)});
  return images;
}

}  // namespace shadowcert::cli
