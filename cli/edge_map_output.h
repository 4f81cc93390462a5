#pragma once
// What `shadowcert diff --edges` adds to its outputs (docs/edge-maps.md#scores): the GL edge
// maps of every filter scored against the exact ground truth (pipeline/edge_map_comparison.h),
// as a table on stdout, the JSON key "edge_maps", PNG files in --out and images in the report.
// `shadowcert edges` can print and write the same for its one filter.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "cli/diff_report.h"
#include "pipeline/edge_map_comparison.h"

namespace shadowcert::cli {

// One line per filter and class at the filter's default thresholds (edge_score_rows: those
// `shadowcert edges` draws with, nothing fitted): P, R and F1 at every tolerance, and the false
// edges on grazing pixels at the first.
void print_edge_maps(const EdgeMapComparison& comparison);

// {"crease_angle", "grazing_angle", "truth": {"profile_pixels", "inner_pixels",
//  "excluded_pixels", "grazing_pixels", "seconds", ...}, "tolerances": [...], "filters":
//  {FILTER: {CLASS: {"thresholds": {"profile", "inner"} (the ones the class read: profile's,
//  inner's, both for any), TOLERANCE: {"precision", "recall", "f1", "detections",
//  "true_detections", "truth", "found", "grazing_false", "grazing_pixels"}}}}}
[[nodiscard]] nlohmann::json edge_maps_json(const EdgeMapComparison& comparison, double crease_degrees,
                                            double grazing_degrees);

// edge_map_pictures as DIR/NAME.png.
void write_edge_map_pictures(const std::filesystem::path& dir, const EdgeMapComparison& comparison);

// The report's facts (one per filter) and its images (one section, "edge maps").
[[nodiscard]] std::vector<std::pair<std::string, std::string>> edge_map_facts(const EdgeMapComparison& comparison);
[[nodiscard]] std::vector<ReportImage> edge_map_report_images(const EdgeMapComparison& comparison);

}  // namespace shadowcert::cli
