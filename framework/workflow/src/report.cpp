#include <algorithm>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "geotandem/core/atomic_file.hpp"
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

// The surface column: closed by itself, closed by caps on the faces that cut it, or open (a store
// written before caps).
std::string surface_text(const ReportComponent& c) {
  if (!c.closed) return "cut by border (open)";
  if (c.cut_faces.empty() || c.cut_faces == "border") return "closed";
  return "cut " + c.cut_faces + ", capped";
}

// "m^2*ms" as a reader writes it: m²·ms.
std::string pretty_unit(const std::string& unit) {
  std::string out;
  for (std::size_t n = 0; n < unit.size(); ++n) {
    if (unit.compare(n, 2, "^2") == 0) {
      out += "\u00b2";
      ++n;
    } else if (unit.compare(n, 2, "^3") == 0) {
      out += "\u00b3";
      ++n;
    } else if (unit[n] == '*') {
      out += "\u00b7";
    } else {
      out += unit[n];
    }
  }
  return out;
}

// What the recipe's input and execution sections say, in a sentence each.
std::string describe_input(const nlohmann::json& recipe) {
  if (!recipe.is_object() || !recipe.contains("input")) return "";
  const auto& in = recipe["input"];
  std::ostringstream s;
  if (in.contains("synthetic")) {
    const auto& syn = in["synthetic"];
    s << "synthetic " << syn.value("kind", "") << " cube";
    if (syn.contains("shape") && syn["shape"].size() == 3)
      s << " of " << syn["shape"][0] << " &times; " << syn["shape"][1] << " &times; " << syn["shape"][2] << " samples";
    s << ", seed " << syn.value("seed", 0);
    if (syn.contains("snr") && syn["snr"].is_number()) s << ", SNR " << syn["snr"].get<double>();
  } else if (in.contains("file")) {
    s << "<code>" << escape(in["file"].get<std::string>()) << "</code>";
  }
  return s.str();
}

std::string describe_execution(const nlohmann::json& recipe, long long used) {
  if (!recipe.is_object() || !recipe.contains("execution")) return "";
  const auto& ex = recipe["execution"];
  std::string scheduler = ex.value("scheduler", "local");
  long long workers = used >= 0 ? used : ex.value("workers", 1);
  if (scheduler == "local" && workers <= 1) return "local, in this process";
  if (scheduler == "local") return std::to_string(workers) + " local worker processes";
  return std::to_string(workers) + " worker(s) as <b>" + escape(scheduler) + "</b> jobs";
}

const char* style =
    R"(body{font-family:system-ui,-apple-system,"Segoe UI",sans-serif;margin:24px auto;max-width:1100px;color:#222;padding:0 16px}
h1{font-size:22px;margin-bottom:4px}h2{font-size:17px;margin-top:28px;border-bottom:1px solid #ddd;padding-bottom:4px}
.meta{color:#666;font-size:13px}table{border-collapse:collapse;font-size:13px}td,th{padding:3px 10px;border-bottom:1px solid #eee;text-align:right}
th{background:#f6f6f6}td.l,th.l{text-align:left}.plots{display:flex;flex-wrap:wrap;gap:24px;align-items:flex-start}
figure{margin:0}figcaption{font-size:12px;color:#555;max-width:520px}pre{background:#f7f7f7;padding:10px;font-size:12px;overflow:auto;max-height:360px}
.kept{color:#1d5680;font-weight:600}.removed{color:#999}dl.facts{display:grid;grid-template-columns:max-content auto;gap:4px 16px;font-size:14px;margin:8px 0}
dl.facts dt{color:#555}dl.facts dd{margin:0}td.sep{border-top:2px solid #bbb}
canvas#gt-view{width:640px;height:480px;border:1px solid #ddd;display:block;cursor:grab}svg.map{border:1px solid #ddd})";

// "N kept bodies", or "N largest (by triangles) of the M kept bodies" when the views leave some out.
std::string shown_bodies(const ReportData& d) {
  std::size_t kept = 0;
  for (const auto& c : d.components)
    if (c.kept) ++kept;
  if (kept <= d.bodies.size()) return std::to_string(d.bodies.size()) + " kept bodies";
  return std::to_string(d.bodies.size()) + " largest (by triangles) of the " + std::to_string(kept) +
         " kept bodies (remove_bubbles keeps fewer)";
}

} // namespace

std::string render_report(const ReportData& d) {
  std::ostringstream h;
  h << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>" << escape(d.title)
    << "</title><style>" << style << "</style></head><body>\n";
  h << "<h1>" << escape(d.title) << "</h1><div class=\"meta\">recipe <code>" << escape(d.recipe_path)
    << "</code> &middot; started " << escape(d.started) << " &middot; " << fixed(d.total_seconds, 1)
    << " s &middot; peak memory " << fixed(static_cast<double>(d.peak_rss_kb) / 1024.0, 0) << " MiB</div>\n";

  const std::string unit = pretty_unit(d.volume_unit);
  std::size_t kept = static_cast<std::size_t>(
      std::count_if(d.components.begin(), d.components.end(), [](const ReportComponent& c) { return c.kept; }));
  h << "<h2>Summary</h2><dl class=\"facts\">";
  if (std::string input = describe_input(d.recipe); !input.empty()) h << "<dt>input</dt><dd>" << input << "</dd>";
  h << "<dt>components</dt><dd>" << d.components.size() << " components extracted, <span class=\"kept\">" << kept
    << " kept</span> after the component steps</dd>";
  // Which side of iso the bodies are (issue 54): the extract step's parameters in the recipe.
  if (d.recipe.is_object() && d.recipe.contains("steps"))
    for (const auto& step : d.recipe["steps"])
      if (step.value("step", "") == "extract" && step.contains("params") && step["params"].contains("iso")) {
        const auto& p = step["params"];
        const bool below = p.value("side", "above") == "below";
        h << "<dt>inside</dt><dd>samples " << (below ? "&le; " : "&ge; ") << escape(p["iso"].get<std::string>())
          << " (side " << (below ? "below" : "above") << ")</dd>";
      }
  if (d.bubble_threshold > 0)
    h << "<dt>bubble threshold</dt><dd>" << sci(d.bubble_threshold) << " " << escape(unit)
      << " (components below it were removed)</dd>";
  if (std::string execution = describe_execution(d.recipe, d.extract_workers); !execution.empty())
    h << "<dt>execution</dt><dd>" << execution << "</dd>";
  h << "</dl>\n";

  h << "<h2>Steps</h2><table><tr><th class=\"l\">step</th><th>seconds</th><th>before</th><th>after</th><th "
       "class=\"l\">note</th></tr>";
  for (const auto& s : d.steps) {
    // The extraction has no components before it: a dash reads better than a zero.
    std::string before = s.name == "extract" ? "&ndash;" : std::to_string(s.count_before);
    h << "<tr><td class=\"l\">" << escape(s.name) << "</td><td>" << fixed(s.seconds, 2) << "</td><td>" << before
      << "</td><td>" << s.count_after << "</td><td class=\"l\">" << escape(pretty_unit(s.note)) << "</td></tr>";
  }
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
    << svg_volume_histogram(volumes, d.bubble_threshold, unit)
    << "<figcaption>Volumes of all closed components; grey bars fall below the bubble threshold (dashed red "
       "line).</figcaption></figure><figure>"
    << svg_series(d.triangles_per_layer, "layer", "triangles in memory")
    << "<figcaption>Triangles held in memory after each extracted layer (the seed's figure "
       "11).</figcaption></figure></div>\n";

  if (d.survey.known) {
    h << "<h2>Bodies</h2><div class=\"plots\"><figure>" << svg_body_map(d.survey, d.bodies)
      << "<figcaption>Map view, north up: the survey outline and the footprint (convex hull of the surface seen "
         "from above) of each of the "
      << shown_bodies(d)
      << ", coloured by the azimuth of its main axis. Hover a footprint for its key.</figcaption>"
         "</figure><figure>"
      << body_viewer_html(d.survey, d.bodies, unit)
      << "<figcaption>3-D view: drag to orbit, wheel to zoom, right-drag to pan; click a body. The survey's box is "
         "drawn in grey, north by the arrow; the vertical axis is exaggerated so that the cube is half as high as "
         "it is wide (1 "
      << escape(d.survey.z_unit) << " = " << fixed(display_z_scale(d.survey), 2)
      << " m). Bodies with more than their share of " << kDisplayTriangleBudget
      << " triangles are decimated for display.</figcaption></figure></div>\n";
  }

  // Every kept component (a body cut by the border has no enclosed volume but is kept by its area,
  // so sorting all components by volume alone would hide it), then the largest removed ones.
  auto by_volume = [](const ReportComponent& a, const ReportComponent& b) {
    if (a.volume != b.volume) return a.volume > b.volume;
    return a.triangles > b.triangles;
  };
  std::vector<ReportComponent> kept_list, removed_list;
  for (const auto& c : d.components)
    (c.kept ? kept_list : removed_list).push_back(c);
  std::sort(kept_list.begin(), kept_list.end(), by_volume);
  std::sort(removed_list.begin(), removed_list.end(), by_volume);
  const std::size_t shown_removed = std::min<std::size_t>(removed_list.size(), kept_list.size() < 40 ? 15 : 5);
  h << "<h2>Components</h2><p class=\"meta\">All " << kept_list.size() << " kept components";
  if (shown_removed) h << ", then the " << shown_removed << " largest of the " << removed_list.size() << " removed";
  h << ". <code>geotandem store ls</code> lists every one.</p><table><tr><th>#</th><th>key</th><th>volume (" << unit
    << ")</th><th>azimuth (&deg;)</th><th>elongation</th><th>triangles</th><th class=\"l\">surface</th><th "
       "class=\"l\">status</th></tr>";
  auto row = [&](const ReportComponent& c, std::size_t rank, bool separator) {
    const char* td = separator ? "<td class=\"sep\">" : "<td>";
    h << "<tr>" << td << rank << "</td>" << td << c.key << "</td>" << td
      << (c.closed ? sci(c.volume) : std::string("&ndash;")) << "</td>" << td << fixed(c.azimuth, 1) << "</td>" << td
      << fixed(c.elongation, 2) << "</td>" << td << c.triangles << "</td><td class=\"l" << (separator ? " sep" : "")
      << "\">" << surface_text(c) << "</td><td class=\"l " << (separator ? "sep " : "")
      << (c.kept ? "kept\">kept" : "removed\">removed") << "</td></tr>";
  };
  for (std::size_t n = 0; n < kept_list.size(); ++n)
    row(kept_list[n], n + 1, false);
  for (std::size_t n = 0; n < shown_removed; ++n)
    row(removed_list[n], kept_list.size() + n + 1, n == 0 && !kept_list.empty());
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
  // Renamed into place when whole: two runs never leave one report made of both (AtomicFile).
  write_file_atomically(path, render_report(data), "the report");
}

} // namespace geotandem::workflow
