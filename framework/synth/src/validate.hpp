#pragma once
// Option checks shared by both kinds. Each throws InvalidArgument whose message names the option,
// its value and the valid range.

#include <string>

#include "geotandem/synth/options.hpp"

namespace geotandem::synth::detail {

struct Range {
  double lo, hi;
  bool lo_open = false, hi_open = false;
};

void check_range(const std::string& option, double value, const Range& range, const std::string& unit = {});
void check_shape(const std::string& option, const volume::Index3& shape);
void check_survey(const SurveyOptions& survey);

} // namespace geotandem::synth::detail
