// libFuzzer target: the SEG-Y reader's headers (textual, binary, trace headers, line geometry). The
// input is written as a .segy file and opened; when it opens, a small box is read.

#include <algorithm>
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
  static const ScratchPath scratch(".segy");
  const std::string& path = scratch.str();
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  // Strict first (an irregular survey is refused, naming what it lacks), then with missing samples
  // read (an irregular survey opens, its missing traces read as missing samples).
  for (auto policy : {volume::NanPolicy::error, volume::NanPolicy::fill}) {
    try {
      auto volume = volume::open_volume(path, {.nan_policy = policy});
      const auto& shape = volume->geometry().shape;
      volume::Box box{{0, 0, 0},
                      {std::min<std::int64_t>(shape[0], 2), std::min<std::int64_t>(shape[1], 2),
                       std::min<std::int64_t>(shape[2], 8)}};
      std::vector<float> samples(box.count());
      volume->read(box, samples);
      volume->format_details();
      return 0;
    } catch (const Error&) {
    }
  }
  return 0;
}
