#pragma once
// `shadowcert diff --report FILE.html`: one self-contained HTML page with the diff's table and
// its images side by side. Every image is inlined as a base64 data: URI and the page has no
// script, font or style sheet from elsewhere, so it is viewable offline and can be mailed.
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace shadowcert::cli {

struct ReportImage {
  std::string caption;
  std::vector<std::uint8_t> png;  // the PNG file's bytes
};

// One row of the table: a method's figures (docs/definitions.md#pixel-protocol, docs/definitions.md#speed-against-error).
struct ReportRow {
  std::string method;
  bool robust = true;            // its hard errors and open volumes fail the run
  std::uint64_t hard_errors = 0;
  std::uint64_t ambiguous = 0;
  std::uint64_t agree = 0;
  std::optional<bool> closed;    // none for a method without a volume
  double gl_ms = 0.0;
  std::string note;              // e.g. the shadow map's size
};

// One entry of a colour legend: a swatch and what it means.
struct LegendSwatch {
  std::string label;
  std::array<std::uint8_t, 3> colour{};
};

// The legend of the exact counts in viridis (pipeline/comparison_pictures.h's count_colour_image
// up to `scale_max`): every count 0..scale_max when scale_max <= 16, else five evenly spaced;
// then "undefined" (magenta).
[[nodiscard]] std::vector<LegendSwatch> counts_legend(std::uint32_t scale_max);

struct DiffReport {
  std::string title;
  std::vector<std::pair<std::string, std::string>> facts;  // "what: value" lines above the table
  std::vector<ReportRow> rows;
  std::vector<ReportImage> exact_images;
  std::vector<LegendSwatch> counts_legend;  // shown under the exact images (the counts in viridis)
  std::vector<std::pair<std::string, std::vector<ReportImage>>> method_images;  // per method name
  bool passed = true;
};

// RFC 4648 base64 of `bytes` (with '=' padding).
[[nodiscard]] std::string base64(std::span<const std::uint8_t> bytes);
// `text` with &, <, >, " and ' escaped for HTML text and attribute values.
[[nodiscard]] std::string html_escape(std::string_view text);
// The page's HTML.
[[nodiscard]] std::string diff_report_html(const DiffReport& report);
// Writes the page, creating parent folders; throws InputError naming the file on failure.
void write_diff_report(const std::filesystem::path& file, const DiffReport& report);

}  // namespace shadowcert::cli
