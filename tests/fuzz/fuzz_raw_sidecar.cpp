// libFuzzer target: the raw cube's JSON sidecar. The input is written as FILE.raw.json beside a
// 4096-byte FILE.raw, then the cube is opened (and, when it opens, one sample is read).

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "geotandem/core/error.hpp"
#include "geotandem/volume/io.hpp"
#include "scratch_path.hpp"

using namespace geotandem;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const ScratchPath scratch_cube("-raw.raw"), scratch_sidecar("-raw.raw.json");
  const std::string& cube = scratch_cube.str();
  static const bool made = [&cube] {
    std::ofstream(cube, std::ios::binary) << std::string(4096, '\0');
    return true;
  }();
  (void)made;
  std::ofstream(scratch_sidecar.str(), std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  try {
    auto volume = volume::open_volume(cube);
    std::vector<float> one(1);
    volume->read(volume::Box{{0, 0, 0}, {1, 1, 1}}, one);
  } catch (const Error&) {
  }
  return 0;
}
