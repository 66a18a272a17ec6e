#pragma once
// The geometry of a seismic cube: its shape along (inline, crossline, sample), the line numbers of
// its first traces, the sample axis, and the survey affine from (inline index, crossline index) to
// world map coordinates. World x is east, y is north (metres); z is the sample axis, down, in
// milliseconds (time) or metres (depth).

#include <array>
#include <string>

#include "geotandem/volume/box.hpp"

namespace geotandem::volume {

// Time (ms), depth in metres or depth in feet (international foot), as the file says. A sample
// axis in seconds is read as milliseconds.
enum class SampleUnit { milliseconds, metres, feet };

// "ms", "m" or "ft"; parse_sample_unit throws InvalidArgument on anything else.
const char* to_string(SampleUnit unit);
SampleUnit parse_sample_unit(const std::string& text);

// The coordinate reference system of the map coordinates (x, y), as GDAL's OSR understood the
// text a file or a user gave (volume/crs.hpp parses it). Everything a program needs to show it is
// kept here as text, so that reading a store or an export needs no GDAL. Empty (no wkt): none was
// given, and outputs say "no CRS given" rather than inventing one; x and y are then taken as metres.
struct Crs {
  std::string name;             // "ED50 / UTM zone 31N"
  std::string code;             // "EPSG:23031" when OSR identifies an authority code, else ""
  std::string wkt;              // WKT 2 (2019) as OSR writes it; "" when no CRS was given
  std::string unit = "m";       // the linear unit of x and y: "m", "ft" (international foot), "ftUS"
  std::string unit_name;        // as OSR names it: "metre", "foot", "US survey foot"
  double metres_per_unit = 1.0; // of `unit`
  bool empty() const { return wkt.empty(); }
  // "ED50 / UTM zone 31N (EPSG:23031)", or "no CRS given".
  std::string label() const;
  bool operator==(const Crs&) const = default;
};
inline constexpr const char* kNoCrs = "no CRS given";

// World map coordinates of the trace at array indices (i, j):
//   x = x0 + xi * i + xj * j,   y = y0 + yi * i + yj * j.
// Fitted from three corner traces, as interpretation systems keep it. Bins need not be square
// or orthogonal to north, so orientations are always computed through this affine.
struct SurveyAffine {
  double x0 = 0.0, xi = 25.0, xj = 0.0;
  double y0 = 0.0, yi = 0.0, yj = 25.0;

  std::array<double, 2> apply(double i, double j) const { return {x0 + xi * i + xj * j, y0 + yi * i + yj * j}; }
  // Distances in metres between neighbouring inlines (along i) and crosslines (along j).
  double step_i() const;
  double step_j() const;
  bool operator==(const SurveyAffine&) const = default;
};

struct Geometry {
  Index3 shape{0, 0, 0};    // number of inlines, crosslines, samples
  double inline0 = 1.0;     // inline number of index i = 0
  double inline_step = 1.0; // inline number increment per index
  double crossline0 = 1.0;  // crossline number of index j = 0
  double crossline_step = 1.0;
  double z0 = 0.0; // z of sample k = 0, in `z_unit`
  double dz = 4.0; // sample interval, in `z_unit` (> 0)
  SampleUnit z_unit = SampleUnit::milliseconds;
  SurveyAffine affine{};
  // Of the map coordinates the affine gives. Not part of the grid: two geometries of one grid with
  // different CRSs describe the same samples (same_grid).
  Crs crs{};

  Box bounds() const { return Box::of_shape(shape); }
  std::size_t sample_count() const { return bounds().count(); }
  // World coordinates (x, y, z) of a point given in (fractional) index coordinates.
  std::array<double, 3> world(double i, double j, double k) const;
  // Throws InvalidArgument naming the offending field when the geometry cannot describe a cube
  // (non-positive shape or dz, degenerate affine).
  void validate() const;
  // Everything but the CRS is equal: the same samples at the same places in the same numbers.
  bool same_grid(const Geometry& other) const;
  bool operator==(const Geometry&) const = default;
};

// The unit of enclosed volumes in this geometry's world coordinates: "m^3", "m^2*ms", "ft^3",
// "ft^2*ms", "ftUS^2*ft", ... (the CRS's linear unit squared times the sample unit).
std::string volume_unit(const Geometry& geometry);

} // namespace geotandem::volume
