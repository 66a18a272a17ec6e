#pragma once
// What the schedule tests (schedule_test.cpp, schedule_properties_test.cpp) share.

#include <cstdint>

#include "geotandem/volume/box.hpp"

namespace geotandem::runtime::schedule_test {

// The cells of a cube of x * y * z cells, from the origin.
inline volume::Box cells(std::int64_t x, std::int64_t y, std::int64_t z) {
  return volume::Box{{0, 0, 0}, {x, y, z}};
}

} // namespace geotandem::runtime::schedule_test
