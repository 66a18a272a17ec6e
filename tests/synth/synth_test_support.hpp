#pragma once
// Small helpers shared by the synth tests.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "geotandem/synth/synthetic.hpp"

namespace geotandem::synth::test {

inline double dimension(const Body& body, const std::string& name) {
  for (const auto& [key, value] : body.dimensions)
    if (key == name) return value;
  ADD_FAILURE() << body.name << " has no dimension " << name;
  return std::nan("");
}

// Smallest difference between two axial angles (degrees, period 180).
inline double axial_difference(double a, double b) {
  double d = std::fmod(std::abs(a - b), 180.0);
  return std::min(d, 180.0 - d);
}

// Does the sample box of a component lie inside a body's index bounds (with half a sample slack)?
template <class Component> bool inside_bounds(const Component& c, const Body& body) {
  for (int a = 0; a < 3; ++a)
    if (static_cast<double>(c.lo[a]) < body.bounds_lo[a] - 0.5 ||
        static_cast<double>(c.hi[a]) > body.bounds_hi[a] + 0.5)
      return false;
  return true;
}

} // namespace geotandem::synth::test
