#include "geotandem/synth/synthetic.hpp"

namespace geotandem::synth {

std::string SyntheticCube::format() const {
  return std::string("synthetic ") + to_string(truth_.kind);
}

std::string SyntheticCube::source() const {
  const auto& s = truth_.geometry.shape;
  return "synthetic " + std::string(to_string(truth_.kind)) + " cube (seed " + std::to_string(truth_.seed) + ", " +
         std::to_string(s[0]) + "x" + std::to_string(s[1]) + "x" + std::to_string(s[2]) + ")";
}

} // namespace geotandem::synth
