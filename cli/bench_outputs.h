#pragma once
// The outputs of `shadowcert bench` that are functions of bench.json alone (docs/bench.md), so
// that `bench --from FILE` rewrites them from a shard merge without rendering:
//   bench.csv    one row per scene and run, every headline figure (columns in kBenchCsvColumns)
//   bench.md     the tables, ready for docs: the runs summed over the scenes, the contour and
//                analytic tables of the analytic suite, the soft-shadow error per scene, every
//                scene's runs
//   report.html  one offline page (images and plots inlined as data: URIs, no script): the same
//                tables, the plots (DIR/plots/index.json), each scene's exact pictures (the counts
//                in viridis with their legend) and each run's overlay
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace shadowcert::cli {

[[nodiscard]] std::string bench_csv(const nlohmann::json& bench);
[[nodiscard]] std::string bench_markdown(const nlohmann::json& bench);
// `dir`: where the images the JSON names (relative paths) and plots/ lie; a missing image is
// named in the page. `plots_note`: why there are no plots, or empty.
[[nodiscard]] std::string bench_report_html(const nlohmann::json& bench, const std::filesystem::path& dir,
                                            const std::string& plots_note);

}  // namespace shadowcert::cli
