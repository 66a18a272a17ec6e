// Inline SVG plots for the run report. Plain text generation: no scripts, no external fonts.

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <numbers>
#include <sstream>

#include "geotandem/workflow/report.hpp"

namespace geotandem::workflow {
namespace {

std::string num(double v, int precision = 1) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(precision) << v;
  return out.str();
}

// "1.2e5"-style tick labels for log axes.
std::string power_label(int exponent) {
  return "1e" + std::to_string(exponent);
}

} // namespace

std::string svg_rose(const std::vector<double>& azimuths, const std::vector<double>& weights, int bins) {
  // Axial data: each bin over [0, 180) is drawn twice, at theta and theta + 180 (bidirectional).
  bins = std::max(1, bins);
  std::vector<double> count(static_cast<std::size_t>(bins), 0.0);
  for (std::size_t n = 0; n < azimuths.size(); ++n) {
    double a = std::fmod(std::fmod(azimuths[n], 180.0) + 180.0, 180.0);
    auto b = std::min<std::size_t>(static_cast<std::size_t>(a / 180.0 * bins), count.size() - 1);
    count[b] += weights.empty() ? 1.0 : weights[n];
  }
  double top = *std::max_element(count.begin(), count.end());
  const double cx = 160, cy = 160, r = 130;
  std::ostringstream s;
  s << "<svg class=\"rose\" xmlns=\"http://www.w3.org/2000/svg\" width=\"320\" height=\"330\" viewBox=\"0 0 320 330\">"
    << "<title>Azimuth rose diagram (bidirectional)</title>";
  for (double f : {0.25, 0.5, 0.75, 1.0})
    s << "<circle cx=\"" << cx << "\" cy=\"" << cy << "\" r=\"" << num(r * f) << "\" fill=\"none\" stroke=\"#ccc\"/>";
  for (int d = 0; d < 180; d += 30) {
    double t = d * std::numbers::pi / 180.0;
    s << "<line x1=\"" << num(cx - r * std::sin(t)) << "\" y1=\"" << num(cy + r * std::cos(t)) << "\" x2=\""
      << num(cx + r * std::sin(t)) << "\" y2=\"" << num(cy - r * std::cos(t)) << "\" stroke=\"#e3e3e3\"/>";
  }
  const double width = std::numbers::pi / bins;
  for (int b = 0; b < bins && top > 0; ++b) {
    double len = r * std::sqrt(count[static_cast<std::size_t>(b)] / top); // area-true petals
    if (len <= 0) continue;
    for (double offset : {0.0, std::numbers::pi}) {
      double t0 = b * width + offset, t1 = (b + 1) * width + offset;
      // Azimuth is clockwise from north: x = sin, y = -cos on screen.
      s << "<path class=\"petal\" d=\"M" << cx << "," << cy << " L" << num(cx + len * std::sin(t0)) << ","
        << num(cy - len * std::cos(t0)) << " A" << num(len) << "," << num(len) << " 0 0 1 "
        << num(cx + len * std::sin(t1)) << "," << num(cy - len * std::cos(t1))
        << " Z\" fill=\"#2b7bb9\" fill-opacity=\"0.75\" stroke=\"#1d5680\" stroke-width=\"0.5\"/>";
    }
  }
  s << "<text x=\"" << cx << "\" y=\"18\" text-anchor=\"middle\" font-size=\"13\">N</text>"
    << "<text x=\"" << cx + r + 14 << "\" y=\"" << cy + 4 << "\" text-anchor=\"middle\" font-size=\"13\">E</text>"
    << "<text x=\"" << cx << "\" y=\"" << cy + r + 24 << "\" text-anchor=\"middle\" font-size=\"11\">"
    << azimuths.size() << " components, " << bins << " bins of " << num(180.0 / bins, 0) << "&#176;</text></svg>";
  return s.str();
}

std::string svg_volume_histogram(const std::vector<double>& volumes, double threshold, const std::string& unit) {
  const double width = 520, height = 260, left = 56, right = 12, top = 14, bottom = 44;
  std::vector<double> logs;
  for (double v : volumes)
    if (v > 0) logs.push_back(std::log10(v));
  std::ostringstream s;
  s << "<svg class=\"histogram\" xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
    << "\" viewBox=\"0 0 " << width << " " << height << "\"><title>Component volumes (log scale)</title>";
  if (logs.empty()) {
    s << "<text x=\"" << width / 2 << "\" y=\"" << height / 2
      << "\" text-anchor=\"middle\">no closed components</text></svg>";
    return s.str();
  }
  double lo = std::floor(*std::min_element(logs.begin(), logs.end()));
  double hi = std::ceil(*std::max_element(logs.begin(), logs.end()));
  if (threshold > 0) {
    lo = std::min(lo, std::floor(std::log10(threshold)));
    hi = std::max(hi, std::ceil(std::log10(threshold)));
  }
  if (hi <= lo) hi = lo + 1;
  const int bins = std::clamp(static_cast<int>((hi - lo) * 5), 5, 60);
  std::vector<std::size_t> count(static_cast<std::size_t>(bins), 0);
  for (double l : logs)
    ++count[std::min<std::size_t>(static_cast<std::size_t>((l - lo) / (hi - lo) * bins), count.size() - 1)];
  std::size_t peak = *std::max_element(count.begin(), count.end());
  double peak_log = std::log10(static_cast<double>(peak) + 1.0);
  double pw = width - left - right, ph = height - top - bottom;
  auto x_of = [&](double l) { return left + (l - lo) / (hi - lo) * pw; };
  // Counts on a log scale too: the bubbles outnumber the bodies by orders of magnitude.
  auto y_of = [&](std::size_t c) { return top + ph - ph * std::log10(static_cast<double>(c) + 1.0) / peak_log; };
  s << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << pw << "\" height=\"" << ph
    << "\" fill=\"none\" stroke=\"#999\"/>";
  for (int b = 0; b < bins; ++b) {
    std::size_t c = count[static_cast<std::size_t>(b)];
    if (!c) continue;
    double x0 = x_of(lo + (hi - lo) * b / bins), x1 = x_of(lo + (hi - lo) * (b + 1) / bins);
    double lb = lo + (hi - lo) * (b + 0.5) / bins;
    bool removed = threshold > 0 && lb < std::log10(threshold);
    s << "<rect class=\"bar\" x=\"" << num(x0 + 0.5) << "\" y=\"" << num(y_of(c)) << "\" width=\""
      << num(std::max(0.5, x1 - x0 - 1)) << "\" height=\"" << num(top + ph - y_of(c)) << "\" fill=\""
      << (removed ? "#c9c9c9" : "#2b7bb9") << "\"><title>" << c << " components</title></rect>";
  }
  for (int e = static_cast<int>(lo); e <= static_cast<int>(hi); ++e)
    s << "<text x=\"" << num(x_of(e)) << "\" y=\"" << height - bottom + 16
      << "\" text-anchor=\"middle\" font-size=\"11\">" << power_label(e) << "</text>";
  s << "<text x=\"" << left + pw / 2 << "\" y=\"" << height - 6 << "\" text-anchor=\"middle\" font-size=\"12\">volume ("
    << unit << ", log scale)</text>"
    << "<text x=\"14\" y=\"" << top + ph / 2 << "\" text-anchor=\"middle\" font-size=\"12\" transform=\"rotate(-90 14 "
    << top + ph / 2 << ")\">components (log)</text>"
    << "<text x=\"" << left - 4 << "\" y=\"" << top + 10 << "\" text-anchor=\"end\" font-size=\"10\">" << peak
    << "</text>";
  if (threshold > 0) {
    double x = x_of(std::log10(threshold));
    s << "<line class=\"threshold\" x1=\"" << num(x) << "\" y1=\"" << top << "\" x2=\"" << num(x) << "\" y2=\""
      << top + ph << "\" stroke=\"#d62728\" stroke-width=\"2\" stroke-dasharray=\"5,3\"/>"
      << "<text x=\"" << num(x + 4) << "\" y=\"" << top + 12
      << "\" font-size=\"11\" fill=\"#d62728\">bubble threshold</text>";
  }
  s << "</svg>";
  return s.str();
}

std::string svg_series(const std::vector<std::uint64_t>& values, const std::string& x_label,
                       const std::string& y_label) {
  const double width = 520, height = 240, left = 64, right = 12, top = 14, bottom = 40;
  std::ostringstream s;
  s << "<svg class=\"series\" xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
    << "\" viewBox=\"0 0 " << width << " " << height << "\"><title>" << y_label << "</title>";
  if (values.empty()) {
    s << "<text x=\"" << width / 2 << "\" y=\"" << height / 2 << "\" text-anchor=\"middle\">no data</text></svg>";
    return s.str();
  }
  double peak = static_cast<double>(std::max<std::uint64_t>(1, *std::max_element(values.begin(), values.end())));
  double pw = width - left - right, ph = height - top - bottom;
  s << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << pw << "\" height=\"" << ph
    << "\" fill=\"none\" stroke=\"#999\"/><polyline class=\"line\" fill=\"none\" stroke=\"#2b7bb9\" "
       "stroke-width=\"1.5\" points=\"";
  for (std::size_t n = 0; n < values.size(); ++n) {
    double x = left + (values.size() == 1 ? 0.0 : pw * static_cast<double>(n) / static_cast<double>(values.size() - 1));
    double y = top + ph - ph * static_cast<double>(values[n]) / peak;
    s << num(x) << "," << num(y) << " ";
  }
  s << "\"/><text x=\"" << left - 4 << "\" y=\"" << top + 10 << "\" text-anchor=\"end\" font-size=\"10\">"
    << static_cast<std::uint64_t>(peak) << "</text><text x=\"" << left - 4 << "\" y=\"" << top + ph
    << "\" text-anchor=\"end\" font-size=\"10\">0</text>"
    // The first and last x values, so the axis reads without counting.
    << "<text x=\"" << left << "\" y=\"" << top + ph + 14 << "\" text-anchor=\"start\" font-size=\"10\">1</text>"
    << "<text x=\"" << left + pw << "\" y=\"" << top + ph + 14 << "\" text-anchor=\"end\" font-size=\"10\">"
    << values.size() << "</text><text x=\"" << left + pw / 2 << "\" y=\"" << height - 8
    << "\" text-anchor=\"middle\" font-size=\"12\">" << x_label << "</text><text x=\"14\" y=\"" << top + ph / 2
    << "\" text-anchor=\"middle\" font-size=\"12\" transform=\"rotate(-90 14 " << top + ph / 2 << ")\">" << y_label
    << "</text></svg>";
  return s.str();
}

} // namespace geotandem::workflow
