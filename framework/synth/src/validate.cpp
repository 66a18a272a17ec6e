#include "validate.hpp"

#include <cmath>
#include <sstream>

#include "geotandem/core/error.hpp"
#include "geotandem/volume/size_guard.hpp"

namespace geotandem::synth::detail {

void check_range(const std::string& option, double value, const Range& range, const std::string& unit) {
  bool above = range.lo_open ? value > range.lo : value >= range.lo;
  bool below = range.hi_open ? value < range.hi : value <= range.hi;
  if (std::isnan(value) || !above || !below) {
    std::ostringstream text;
    text << "synthetic cube option " << option << " is " << value << (unit.empty() ? "" : " ") << unit
         << "; it must be in " << (range.lo_open ? '(' : '[') << range.lo << ", " << range.hi
         << (range.hi_open ? ')' : ']') << (unit.empty() ? "" : " ") << unit;
    throw InvalidArgument(text.str(), {}, "change " + option);
  }
}

void check_shape(const std::string& option, const volume::Index3& shape) {
  static constexpr const char* axes[] = {"inline", "crossline", "sample"};
  constexpr std::int64_t max_edge = 1 << 20;
  for (int a = 0; a < 3; ++a)
    if (shape[a] < min_edge || shape[a] > max_edge)
      throw InvalidArgument(option + " has " + std::to_string(shape[a]) + " samples along the " + axes[a] +
                                " axis; every axis needs " + std::to_string(min_edge) + " to " +
                                std::to_string(max_edge) + " samples",
                            {}, "the planted bodies need room: use a larger shape");
  volume::check_shape_fits(shape, option);
}

void check_survey(const SurveyOptions& s) {
  const double inf = HUGE_VAL;
  check_range("survey.bin_inline_m", s.bin_inline_m, {0.0, 1e6, true, false}, "m");
  check_range("survey.bin_crossline_m", s.bin_crossline_m, {0.0, 1e6, true, false}, "m");
  // Bins more elongated than 4:1 would squash the smallest bodies to a sample across and stretch
  // bubbles into streaks along the short bin.
  check_range("survey bin aspect ratio (bin_inline_m / bin_crossline_m)", s.bin_inline_m / s.bin_crossline_m,
              {0.25, 4.0});
  check_range("survey.rotation_deg", s.rotation_deg, {-360.0, 360.0}, "degrees");
  check_range("survey.dz", s.dz, {0.0, 1e6, true, false});
  check_range("survey.z0", s.z0, {-inf, inf, true, true});
  check_range("survey.x0", s.x0, {-inf, inf, true, true}, "m");
  check_range("survey.y0", s.y0, {-inf, inf, true, true}, "m");
  check_range("survey.inline0", s.inline0, {-inf, inf, true, true});
  check_range("survey.crossline0", s.crossline0, {-inf, inf, true, true});
}

} // namespace geotandem::synth::detail
