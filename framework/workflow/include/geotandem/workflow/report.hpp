#pragma once
// The run report: one self-contained HTML file (inline CSS and SVG, no scripts, no network) with
// the recipe, timings, counts before and after each step, the largest components, a bidirectional
// rose diagram of azimuths, a log-scale volume histogram with the bubble threshold, and the
// triangles held in memory per layer.

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace geotandem::workflow {

struct ReportComponent {
  std::uint64_t key = 0;
  double volume = 0.0;
  double azimuth = 0.0; // degrees, axial [0, 180)
  double elongation = 0.0;
  std::uint64_t triangles = 0;
  bool closed = false;
  bool kept = false; // survives the component steps
};

struct ReportStep {
  std::string name;
  double seconds = 0.0;
  std::uint64_t count_before = 0; // components (or samples for volume steps)
  std::uint64_t count_after = 0;
  std::string note; // "reused from a previous run", parameters, ...
};

struct ReportData {
  std::string title;
  std::string recipe_path;
  nlohmann::json recipe; // canonical recipe
  std::string started;   // ISO 8601
  double total_seconds = 0.0;
  std::int64_t peak_rss_kb = 0;
  std::string volume_unit = "m^3";
  std::vector<ReportStep> steps;
  std::vector<ReportComponent> components;        // every component of the run
  double bubble_threshold = 0.0;                  // volume below which components were removed; 0: none
  std::vector<std::uint64_t> triangles_per_layer; // in memory after each layer
  int azimuth_bins = 18;
  std::vector<std::string> outputs; // files written, relative to the report
};

// The HTML text. Pure function: tests parse it.
std::string render_report(const ReportData& data);
// Writes render_report(data) to `path`; throws IoError naming the path.
void write_report(const ReportData& data, const std::string& path);

// Plots, exposed for tests: an SVG element each.
std::string svg_rose(const std::vector<double>& azimuths, const std::vector<double>& weights, int bins);
std::string svg_volume_histogram(const std::vector<double>& volumes, double threshold, const std::string& unit);
std::string svg_series(const std::vector<std::uint64_t>& values, const std::string& x_label,
                       const std::string& y_label);

} // namespace geotandem::workflow
