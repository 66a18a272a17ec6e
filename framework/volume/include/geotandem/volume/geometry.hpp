#pragma once
// The geometry of a seismic cube: its shape along (inline, crossline, sample), the line numbers of
// its first traces, the sample axis, and the survey affine from (inline index, crossline index) to
// world map coordinates. World x is east, y is north (metres); z is the sample axis, down, in
// milliseconds (time) or metres (depth).

#include <array>
#include <string>

#include "geotandem/volume/box.hpp"

namespace geotandem::volume {

enum class SampleUnit { milliseconds, metres };

// "ms" or "m"; parse_sample_unit throws InvalidArgument on anything else.
const char* to_string(SampleUnit unit);
SampleUnit parse_sample_unit(const std::string& text);

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

  Box bounds() const { return Box::of_shape(shape); }
  std::size_t sample_count() const { return bounds().count(); }
  // World coordinates (x, y, z) of a point given in (fractional) index coordinates.
  std::array<double, 3> world(double i, double j, double k) const;
  // Throws InvalidArgument naming the offending field when the geometry cannot describe a cube
  // (non-positive shape or dz, degenerate affine).
  void validate() const;
  bool operator==(const Geometry&) const = default;
};

} // namespace geotandem::volume
