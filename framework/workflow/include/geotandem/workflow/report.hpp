#pragma once
// The run report: one self-contained HTML file (inline CSS, SVG and scripts, no network) with
// the recipe, timings, counts before and after each step, the largest components, a bidirectional
// rose diagram of azimuths, a log-scale volume histogram with the bubble threshold, the
// triangles held in memory per layer, and the kept bodies themselves: a map view (inline SVG) and
// an interactive 3-D view (WebGL through three.js from Debian's libjs-three, inlined; see
// report_views.hpp for where the bodies come from).

#include <array>
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
  bool kept = false;     // survives the component steps
  std::string cut_faces; // faces of the cube that cut it ("i-,k+"; empty: none), closed by caps
};

// Triangles the 3-D view holds for all bodies together (about 2 MB of page); bodies above their
// share are decimated for display.
inline constexpr std::size_t kDisplayTriangleBudget = 40000;
// Kept bodies the map and the 3-D view draw at most, the largest by triangles: a recipe that keeps
// every speck of a large cube (no remove_bubbles) would otherwise make a page of hundreds of MB,
// and the footprints of all of them would be held at once.
inline constexpr std::size_t kDisplayBodies = 2000;

// The survey's outline on the map and its sample range, for the body views.
struct ReportSurvey {
  bool known = false;                           // false: no views are drawn
  std::array<std::array<double, 2>, 4> corners; // world x (east), y (north) in xy_unit, in order around
  double z_min = 0.0, z_max = 0.0;              // first and last sample, in z_unit (down)
  std::string z_unit = "ms";
  // The CRS of x and y as the map's axes name it ("ED50 / UTM zone 31N (EPSG:23031)", or "no CRS
  // given"), and their unit ("m", "ft", "ftUS").
  std::string crs = "no CRS given";
  std::string xy_unit = "m";
};

// A kept body as the views draw it.
struct ReportBody {
  std::uint64_t key = 0;
  double volume = 0.0;
  double azimuth = 0.0; // degrees, axial [0, 180)
  bool closed = false;
  std::uint64_t full_triangles = 0; // before decimation for display
  // Surface decimated for display: points relative to the survey's first corner (x, y in metres,
  // z in z_unit), triangles as point indices.
  std::vector<std::array<float, 3>> points;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  // Convex hull of the full-resolution surface projected on the map (world x, y), in order.
  std::vector<std::array<double, 2>> footprint;
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
  // The workers the extraction of this run used (0: in this process); -1 when this run did not
  // extract (a rerun after it): the report then describes the recipe's execution section.
  long long extract_workers = -1;
  std::string started; // ISO 8601
  double total_seconds = 0.0;
  std::int64_t peak_rss_kb = 0;
  std::string volume_unit = "m^3";
  std::vector<ReportStep> steps;
  std::vector<ReportComponent> components;        // every component of the run
  double bubble_threshold = 0.0;                  // volume below which components were removed; 0: none
  std::vector<std::uint64_t> triangles_per_layer; // in memory after each layer
  int azimuth_bins = 18;
  std::vector<std::string> outputs; // files written, relative to the report
  ReportSurvey survey;              // for the map and 3-D views
  std::vector<ReportBody> bodies;   // the kept bodies, decimated (report_views.hpp)
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
// Map view: the survey outline and every body's footprint coloured by azimuth, north arrow, scale
// bar, azimuth colour key.
std::string svg_body_map(const ReportSurvey& survey, const std::vector<ReportBody>& bodies);
// The 3-D view's HTML: a canvas, the bodies as JSON (script id "geotandem-bodies"), three.js and
// the viewer script, all inline; or a note saying why it is missing (no three.js installed).
std::string body_viewer_html(const ReportSurvey& survey, const std::vector<ReportBody>& bodies,
                             const std::string& volume_unit);
// How many metres one z unit is drawn as in the 3-D view: the cube's height is half its width.
double display_z_scale(const ReportSurvey& survey);
// The colour of an azimuth in both views: hue = 2 x azimuth, so that 0 and 180 degrees (the same
// axis) share a colour. "#rrggbb".
std::string azimuth_colour(double azimuth);

} // namespace geotandem::workflow
