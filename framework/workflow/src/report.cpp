#include <algorithm>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "geotandem/core/error.hpp"
#include "geotandem/workflow/report.hpp"

namespace geotandem::workflow {
namespace {

std::string escape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
    case '&': out += "&amp;"; break;
    case '<': out += "&lt;"; break;
    case '>': out += "&gt;"; break;
    case '"': out += "&quot;"; break;
    default: out += c;
    }
  }
  return out;
}

std::string fixed(double v, int precision) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(precision) << v;
  return out.str();
}

std::string sci(double v) {
  std::ostringstream out;
  out << std::setprecision(4) << v;
  return out.str();
}

const char* style =
    R"(body{font-family:system-ui,-apple-system,"Segoe UI",sans-serif;margin:24px auto;max-width:1100px;color:#222;padding:0 16px}
h1{font-size:22px;margin-bottom:4px}h2{font-size:17px;margin-top:28px;border-bottom:1px solid #ddd;padding-bottom:4px}
.meta{color:#666;font-size:13px}table{border-collapse:collapse;font-size:13px}td,th{padding:3px 10px;border-bottom:1px solid #eee;text-align:right}
th{background:#f6f6f6}td.l,th.l{text-align:left}.plots{display:flex;flex-wrap:wrap;gap:24px;align-items:flex-start}
figure{margin:0}figcaption{font-size:12px;color:#555;max-width:520px}pre{background:#f7f7f7;padding:10px;font-size:12px;overflow:auto;max-height:360px}
.kept{color:#1d5680;font-weight:600}.removed{color:#999})";

} // namespace

std::string render_report(const ReportData& d) {
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>" << escape(d.title)
    << "</title><style>" << style << "</style></head><body>\n";
  h << "<h1>" << escape(d.title) << "</h1><div class=\"meta\">recipe <code>" << escape(d.recipe_path)
    << "</code> &middot; started " << escape(d.started) << " &middot; " << fixed(d.total_seconds, 1)
    << " s &middot; peak memory " << fixed(static_cast<double>(d.peak_rss_kb) / 1024.0, 0) << " MiB</div>\n";

  std::size_t kept = static_cast<std::size_t>(
      std::count_if(d.components.begin(), d.components.end(), [](const ReportComponent& c) { return c.kept; }));
  h << "<h2>Summary</h2><p>" << d.components.size() << " components extracted, <span class=\"kept\">" << kept
    << " kept</span> after the component steps";
  if (d.bubble_threshold > 0)
    h << " (bubble threshold " << sci(d.bubble_threshold) << " " << escape(d.volume_unit) << ")";
  h << ".</p>\n";

  h << "<h2>Steps</h2><table><tr><th class=\"l\">step</th><th>seconds</th><th>before</th><th>after</th><th "
       "class=\"l\">note</th></tr>";
  for (const auto& s : d.steps)
    h << "<tr><td class=\"l\">" << escape(s.name) << "</td><td>" << fixed(s.seconds, 2) << "</td><td>" << s.count_before
      << "</td><td>" << s.count_after << "</td><td class=\"l\">" << escape(s.note) << "</td></tr>";
  h << "</table>\n";

  std::vector<double> azimuths, weights, volumes;
  for (const auto& c : d.components) {
    if (c.volume > 0) volumes.push_back(c.volume);
    if (c.kept) {
      azimuths.push_back(c.azimuth);
      weights.push_back(1.0);
    }
  }
  h << "<h2>Plots</h2><div class=\"plots\"><figure>" << svg_rose(azimuths, weights, d.azimuth_bins)
    << "<figcaption>Azimuths of the kept components' main horizontal axes, clockwise from north, drawn at both "
       "&theta; and &theta;+180&deg; (axial data).</figcaption></figure><figure>"
    << svg_volume_histogram(volumes, d.bubble_threshold, d.volume_unit)
    << "<figcaption>Volumes of all closed components; grey bars fall below the bubble threshold (dashed red "
       "line).</figcaption></figure><figure>"
    << svg_series(d.triangles_per_layer, "layer", "triangles in memory")
    << "<figcaption>Triangles held in memory after each extracted layer (the seed's figure "
       "11).</figcaption></figure></div>\n";

  std::vector<ReportComponent> largest = d.components;
  std::sort(largest.begin(), largest.end(), [](const auto& a, const auto& b) { return a.volume > b.volume; });
  if (largest.size() > 25) largest.resize(25);
  h << "<h2>Largest components</h2><table><tr><th>rank</th><th>key</th><th>volume (" << escape(d.volume_unit)
    << ")</th><th>azimuth (&deg;)</th><th>elongation</th><th>triangles</th><th class=\"l\">closed</th><th "
       "class=\"l\">status</th></tr>";
  for (std::size_t n = 0; n < largest.size(); ++n) {
    const auto& c = largest[n];
    h << "<tr><td>" << n + 1 << "</td><td>" << c.key << "</td><td>" << sci(c.volume) << "</td><td>"
      << fixed(c.azimuth, 1) << "</td><td>" << fixed(c.elongation, 2) << "</td><td>" << c.triangles
      << "</td><td class=\"l\">" << (c.closed ? "yes" : "cut by border") << "</td><td class=\"l "
      << (c.kept ? "kept\">kept" : "removed\">removed") << "</td></tr>";
  }
  h << "</table>\n";

  if (!d.outputs.empty()) {
    h << "<h2>Outputs</h2><ul>";
    for (const auto& o : d.outputs)
      h << "<li><a href=\"" << escape(o) << "\">" << escape(o) << "</a></li>";
    h << "</ul>\n";
  }
  h << "<h2>Recipe</h2><pre>" << escape(d.recipe.dump(2)) << "</pre>\n</body></html>\n";
  return h.str();
}

void write_report(const ReportData& data, const std::string& path) {
  std::ofstream out(path, std::ios::trunc);
  out << render_report(data);
  out.close();
  if (!out) throw IoError("cannot write the report", {path}, "check that the output directory is writable");
}

} // namespace geotandem::workflow
