// The report's map view: inline SVG of the survey outline and every kept body's footprint,
// coloured by azimuth, with a north arrow, a scale bar, a colour key, and axes with tick values in
// map coordinates that name the CRS (or say "no CRS given"). North is up.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <limits>
#include <sstream>
#include <vector>

#include "geotandem/workflow/report.hpp"

namespace geotandem::workflow {
namespace {

std::string num(double v) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(1) << v;
  return out.str();
}

// 1, 2 or 5 times a power of ten, at most `limit`.
double nice_length(double limit) {
  if (!(limit > 0.0)) return 1.0;
  const double power = std::pow(10.0, std::floor(std::log10(limit)));
  for (double f : {5.0, 2.0, 1.0})
    if (f * power <= limit) return f * power;
  return power;
}

// A length in the map's unit: km beyond 1000 m; feet stay feet.
std::string length_label(double length, const std::string& unit) {
  std::ostringstream out;
  if (unit == "m" && length >= 1000.0)
    out << length / 1000.0 << " km";
  else
    out << length << " " << unit;
  return out.str();
}

std::string escaped(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '&')
      out += "&amp;";
    else if (c == '"')
      out += "&quot;";
    else
      out += c;
  }
  return out;
}

// Tick values: multiples of a nice step, about `count` of them across [lo, hi].
std::vector<double> ticks(double lo, double hi, int count) {
  std::vector<double> out;
  const double step = nice_length((hi - lo) / count);
  if (!(step > 0.0) || !std::isfinite(lo) || !std::isfinite(hi)) return out;
  for (double v = std::ceil(lo / step) * step; v <= hi + 1e-9 * step && out.size() < 20; v += step)
    out.push_back(v);
  return out;
}

std::string tick_text(double value) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(0) << value;
  return out.str();
}

} // namespace

std::string azimuth_colour(double azimuth) {
  // HSL with hue 2 x azimuth, saturation 0.65, lightness 0.45.
  double a = std::fmod(std::fmod(azimuth, 180.0) + 180.0, 180.0);
  const double h = 2.0 * a / 60.0, s = 0.65, l = 0.45;
  const double c = (1.0 - std::abs(2.0 * l - 1.0)) * s, x = c * (1.0 - std::abs(std::fmod(h, 2.0) - 1.0));
  double r = 0, g = 0, b = 0;
  switch (static_cast<int>(h) % 6) {
  case 0: r = c, g = x; break;
  case 1: r = x, g = c; break;
  case 2: g = c, b = x; break;
  case 3: g = x, b = c; break;
  case 4: r = x, b = c; break;
  default: r = c, b = x; break;
  }
  const double m = l - c / 2.0;
  char text[8];
  std::snprintf(text, sizeof text, "#%02x%02x%02x", static_cast<int>(std::lround((r + m) * 255)),
                static_cast<int>(std::lround((g + m) * 255)), static_cast<int>(std::lround((b + m) * 255)));
  return text;
}

std::string svg_body_map(const ReportSurvey& survey, const std::vector<ReportBody>& bodies) {
  const double width = 560, height = 500, margin = 44, key_height = 80;
  double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
  auto extend = [&](const std::array<double, 2>& p) {
    x0 = std::min(x0, p[0]), x1 = std::max(x1, p[0]), y0 = std::min(y0, p[1]), y1 = std::max(y1, p[1]);
  };
  for (const auto& c : survey.corners)
    extend(c);
  for (const auto& b : bodies)
    for (const auto& p : b.footprint)
      extend(p);
  const double dx = std::max(x1 - x0, 1e-9), dy = std::max(y1 - y0, 1e-9);
  const double scale = std::min((width - 2 * margin) / dx, (height - key_height - 2 * margin) / dy);
  // Centred in the drawing area, north up.
  const double ox = (width - dx * scale) / 2.0, oy = (height - key_height + dy * scale) / 2.0;
  auto sx = [&](double x) { return num(ox + (x - x0) * scale); };
  auto sy = [&](double y) { return num(oy - (y - y0) * scale); };
  auto points = [&](const std::vector<std::array<double, 2>>& ring) {
    std::string out;
    for (const auto& p : ring)
      out += sx(p[0]) + "," + sy(p[1]) + " ";
    return out;
  };

  std::ostringstream s;
  s << "<svg class=\"map\" xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
    << "\" viewBox=\"0 0 " << width << " " << height << "\"><title>Map view of the kept bodies</title>";
  // Axes: the frame of the map's coordinates, ticks in the CRS's unit, labels naming the CRS.
  const double left = ox, right = ox + dx * scale, bottom = oy, top = oy - dy * scale;
  s << "<g class=\"axes\" font-size=\"9\" fill=\"#555\"><rect x=\"" << num(left) << "\" y=\"" << num(top)
    << "\" width=\"" << num(right - left) << "\" height=\"" << num(bottom - top)
    << "\" fill=\"none\" stroke=\"#bbb\" stroke-width=\"0.6\"/>";
  for (double x : ticks(x0, x1, 4))
    s << "<line x1=\"" << sx(x) << "\" y1=\"" << num(bottom) << "\" x2=\"" << sx(x) << "\" y2=\"" << num(bottom + 4)
      << "\" stroke=\"#777\"/><text x=\"" << sx(x) << "\" y=\"" << num(bottom + 13) << "\" text-anchor=\"middle\">"
      << tick_text(x) << "</text>";
  for (double y : ticks(y0, y1, 4))
    s << "<line x1=\"" << num(left - 4) << "\" y1=\"" << sy(y) << "\" x2=\"" << num(left) << "\" y2=\"" << sy(y)
      << "\" stroke=\"#777\"/><text x=\"" << num(left - 6) << "\" y=\"" << sy(y) << "\" text-anchor=\"end\" "
      << "transform=\"rotate(-90 " << num(left - 6) << " " << sy(y) << ")\">" << tick_text(y) << "</text>";
  s << "<text class=\"axis-label\" x=\"" << num((left + right) / 2) << "\" y=\"" << num(bottom + 26)
    << "\" font-size=\"10\" text-anchor=\"middle\">x, easting (" << escaped(survey.xy_unit) << "), "
    << escaped(survey.crs) << "</text>";
  s << "<text class=\"axis-label\" x=\"12\" y=\"" << num((top + bottom) / 2)
    << "\" font-size=\"10\" text-anchor=\"middle\" transform=\"rotate(-90 12 " << num((top + bottom) / 2)
    << ")\">y, northing (" << escaped(survey.xy_unit) << ")</text></g>";
  s << "<polygon class=\"survey\" points=\"" << points({survey.corners.begin(), survey.corners.end()})
    << "\" fill=\"#f4f4f4\" stroke=\"#777\" stroke-width=\"1.2\"><title>survey outline (trace centres)</title>"
       "</polygon>";
  // Largest first, so that small bodies stay visible on top.
  std::vector<const ReportBody*> order;
  for (const auto& b : bodies)
    order.push_back(&b);
  std::stable_sort(order.begin(), order.end(), [](auto* a, auto* b) { return a->volume > b->volume; });
  for (const ReportBody* b : order) {
    const std::string colour = azimuth_colour(b->azimuth);
    std::ostringstream title;
    title << "body " << b->key << ": azimuth " << std::fixed << std::setprecision(1) << b->azimuth << "\u00b0";
    if (b->closed) title << ", volume " << std::defaultfloat << std::setprecision(4) << b->volume;
    if (b->footprint.size() >= 3)
      s << "<polygon class=\"footprint\" data-key=\"" << b->key << "\" points=\"" << points(b->footprint)
        << "\" fill=\"" << colour << "\" fill-opacity=\"0.55\" stroke=\"" << colour << "\" stroke-width=\"1\">";
    else if (!b->footprint.empty())
      s << "<circle class=\"footprint\" data-key=\"" << b->key << "\" cx=\"" << sx(b->footprint[0][0]) << "\" cy=\""
        << sy(b->footprint[0][1]) << "\" r=\"3\" fill=\"" << colour << "\">";
    else
      continue;
    s << "<title>" << title.str() << "</title>" << (b->footprint.size() >= 3 ? "</polygon>" : "</circle>");
  }

  // North arrow, top right.
  const double nx = width - 26, ny = 14;
  s << "<g class=\"north-arrow\"><path d=\"M" << nx << "," << ny << " L" << nx - 8 << "," << ny + 24 << " L" << nx
    << "," << ny + 18 << " L" << nx + 8 << "," << ny + 24 << " Z\" fill=\"#333\"/><text x=\"" << nx << "\" y=\""
    << ny + 38 << "\" font-size=\"12\" text-anchor=\"middle\" fill=\"#333\">N</text></g>";
  // Scale bar, bottom left, about a quarter of the map's width.
  const double metres = nice_length(0.25 * (width - 2 * margin) / scale), bar = metres * scale;
  const double bx = margin, by = height - key_height + 44;
  s << "<g class=\"scale-bar\"><rect x=\"" << bx << "\" y=\"" << num(by) << "\" width=\"" << num(bar)
    << "\" height=\"5\" fill=\"#333\"/><text x=\"" << num(bx + bar / 2) << "\" y=\"" << num(by - 4)
    << "\" font-size=\"11\" text-anchor=\"middle\" fill=\"#333\">" << length_label(metres, survey.xy_unit)
    << "</text></g>";
  // Azimuth colour key, bottom.
  const double kx = margin, ky = height - 22, kw = 180;
  s << "<g class=\"azimuth-key\">";
  for (int n = 0; n < 36; ++n)
    s << "<rect x=\"" << num(kx + kw * n / 36.0) << "\" y=\"" << ky << "\" width=\"" << num(kw / 36.0 + 0.5)
      << "\" height=\"8\" fill=\"" << azimuth_colour(n * 5.0 + 2.5) << "\"/>";
  for (int a : {0, 90, 180})
    s << "<text x=\"" << num(kx + kw * a / 180.0) << "\" y=\"" << ky + 19
      << "\" font-size=\"10\" text-anchor=\"middle\" fill=\"#555\">" << a << "\u00b0</text>";
  s << "<text x=\"" << num(kx + kw + 10) << "\" y=\"" << ky + 8
    << "\" font-size=\"11\" fill=\"#555\">azimuth of the main axis (axial)</text></g>";
  s << "</svg>";
  return s.str();
}

} // namespace geotandem::workflow
