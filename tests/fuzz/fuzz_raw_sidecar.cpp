// libFuzzer target: the raw cube's JSON sidecar. The input is written as FILE.raw.json beside a
// 4096-byte FILE.raw, then the cube is opened (and, when it opens, one sample is read).

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "geotandem/core/error.hpp"
#include "geotandem/volume/io.hpp"

using namespace geotandem;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string base = "/tmp/geotandem-fuzz-raw-" + std::to_string(::getpid());
  static const std::string cube = base + ".raw";
  static const bool made = [] {
    std::ofstream(cube, std::ios::binary) << std::string(4096, '\0');
    return true;
  }();
  (void)made;
  std::ofstream(cube + ".json", std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  try {
    auto volume = volume::open_volume(cube);
    std::vector<float> one(1);
    volume->read(volume::Box{{0, 0, 0}, {1, 1, 1}}, one);
  } catch (const Error&) {
  }
  return 0;
}
