#include "cli/diff_report.h"

#include <fmt/core.h>

#include <cmath>
#include <fstream>

#include "io/output_file.h"
#include "pipeline/comparison_pictures.h"
#include "core/input_error.h"

namespace shadowcert::cli {
namespace {

// Inline only: the page must render with no network (pixelated so single pixels stay visible
// when a small image is scaled up).
constexpr std::string_view kDiffReportStyle = R"(
body { font-family: sans-serif; margin: 1.5em; color: #222; }
table { border-collapse: collapse; margin: 1em 0; }
th, td { border: 1px solid #bbb; padding: 0.3em 0.7em; text-align: right; }
th:first-child, td:first-child { text-align: left; }
tr.fail td { background: #fdd; }
.figures { display: flex; flex-wrap: wrap; gap: 1em; }
figure { margin: 0; }
figure img { max-width: 480px; image-rendering: pixelated; border: 1px solid #ccc; background: #444; }
figcaption { font-size: 0.85em; }
.legend span { display: inline-block; width: 1em; height: 1em; vertical-align: middle; }
)";

std::string figure(const ReportImage& image) {
  return fmt::format("<figure><img alt=\"{0}\" src=\"data:image/png;base64,{1}\"><figcaption>{0}</figcaption></figure>\n",
                     html_escape(image.caption), base64(image.png));
}

std::string figures(const std::vector<ReportImage>& images) {
  std::string html = "<div class=\"figures\">\n";
  for (const ReportImage& image : images) html += figure(image);
  return html + "</div>\n";
}

}  // namespace

std::vector<LegendSwatch> counts_legend(std::uint32_t scale_max) {
  std::vector<LegendSwatch> out;
  const double top = scale_max == 0 ? 1.0 : static_cast<double>(scale_max);
  if (scale_max <= 16) {
    for (std::uint32_t n = 0; n <= scale_max; ++n) out.push_back({std::to_string(n), viridis_colour(n / top)});
  } else {
    for (int q = 0; q <= 4; ++q) {
      const auto n = static_cast<std::uint32_t>(std::lround(top * q / 4.0));
      out.push_back({std::to_string(n), viridis_colour(n / top)});
    }
  }
  out.push_back({"undefined", {255, 0, 255}});
  return out;
}

std::string base64(std::span<const std::uint8_t> bytes) {
  static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 3 <= bytes.size(); i += 3) {
    const std::uint32_t v = std::uint32_t{bytes[i]} << 16 | std::uint32_t{bytes[i + 1]} << 8 | bytes[i + 2];
    for (int shift : {18, 12, 6, 0}) out.push_back(kAlphabet[(v >> shift) & 63]);
  }
  const std::size_t rest = bytes.size() - i;
  if (rest > 0) {
    const std::uint32_t v = std::uint32_t{bytes[i]} << 16 | (rest == 2 ? std::uint32_t{bytes[i + 1]} << 8 : 0u);
    out.push_back(kAlphabet[(v >> 18) & 63]);
    out.push_back(kAlphabet[(v >> 12) & 63]);
    out.push_back(rest == 2 ? kAlphabet[(v >> 6) & 63] : '=');
    out.push_back('=');
  }
  return out;
}

std::string html_escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out.push_back(c);
    }
  }
  return out;
}

std::string diff_report_html(const DiffReport& report) {
  std::string html = fmt::format("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
                                 "<title>{0}</title>\n<style>{1}</style>\n</head>\n<body>\n<h1>{0}</h1>\n",
                                 html_escape(report.title), kDiffReportStyle);
  html += fmt::format("<p><strong>{}</strong></p>\n<ul>\n",
                      report.passed ? "PASSED: no robust method has a hard error or an open volume"
                                    : "FAILED: a robust method has a hard error or an open volume");
  for (const auto& [what, value] : report.facts)
    html += fmt::format("<li>{}: {}</li>\n", html_escape(what), html_escape(value));
  html += "</ul>\n<table>\n<tr><th>method</th><th>hard errors</th><th>ambiguous</th><th>agree</th>"
          "<th>volume closed</th><th>GL ms per frame</th><th>note</th></tr>\n";
  for (const ReportRow& row : report.rows) {
    const bool failed = row.robust && (row.hard_errors > 0 || row.closed == false);
    html += fmt::format("<tr{}><td>{}{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{:.2f}</td><td>{}</td></tr>\n",
                        failed ? " class=\"fail\"" : "", html_escape(row.method), row.robust ? "" : " (baseline)",
                        row.hard_errors, row.ambiguous, row.agree,
                        row.closed ? (*row.closed ? "yes" : "NO") : "-", row.gl_ms, html_escape(row.note));
  }
  html += "</table>\n<p class=\"legend\">Overlays: <span style=\"background:#f00\"></span> hard error, "
          "<span style=\"background:#ff0\"></span> ambiguous pixel (docs/definitions.md#pixel-protocol), over the rendered frame.</p>\n";
  html += "<h2>exact image</h2>\n" + figures(report.exact_images);
  if (!report.counts_legend.empty()) {
    html += "<p class=\"legend\">exact counts n(P), viridis:";
    for (const LegendSwatch& s : report.counts_legend)
      html += fmt::format(" <span style=\"background:rgb({},{},{})\"></span> {}", s.colour[0], s.colour[1], s.colour[2],
                          html_escape(s.label));
    html += "; no hit transparent</p>\n";
  }
  for (const auto& [method, images] : report.method_images)
    html += fmt::format("<h2>{}</h2>\n", html_escape(method)) + figures(images);
  return html + "</body>\n</html>\n";
}

void write_diff_report(const std::filesystem::path& file, const DiffReport& report) {
  create_parent_directories(file);
  std::ofstream out(file, std::ios::binary);
  if (!out) throw InputError(file.string(), "cannot open for writing");
  out << diff_report_html(report);
  if (!out) throw InputError(file.string(), "write failed");
}

}  // namespace shadowcert::cli
