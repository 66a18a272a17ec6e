// Writes the surface-record fuzz target's seeds (surface_records.hpp) into a directory:
//   surface_record_seeds DIR
#include <cstdio>
#include <fstream>
#include <string>

#include "surface_records.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: surface_record_seeds DIR\n");
    return 2;
  }
  const geotandem::fuzz::SurfaceRecords r = geotandem::fuzz::surface_records();
  for (std::size_t i = 0; i < r.records.size(); ++i) {
    const std::string path = std::string(argv[1]) + "/record_" + std::to_string(i) + ".bin";
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(r.records[i].data()), static_cast<std::streamsize>(r.records[i].size()));
    if (!out) {
      std::fprintf(stderr, "surface_record_seeds: cannot write %s\n", path.c_str());
      return 3;
    }
  }
  return 0;
}
