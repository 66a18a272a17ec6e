// bench_box_read: how fast boxes come out of chunked netCDF-4 and Zarr cubes through GDAL,
// compared with reading the same file sequentially (slabs of whole inlines, in storage order) and
// with reading its bytes raw.
//
//   bench_box_read [--dir DIR] [--shape NI NJ NK] [--chunk C] [--box B]
//
// Generates a float32 cube from a formula (default 1024 x 1024 x 512, 2 GiB), writes it once per
// format under DIR (default: build/bench-data of the source tree; existing files of the same
// shape and chunk are reused), then reads it. "cold" figures first drop the file's pages from the
// page cache (fdatasync + posix_fadvise DONTNEED per file), "warm" ones read again at once.
// MB are 10^6 bytes.

#include <fcntl.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <string>
#include <vector>

#include "geotandem/core/error.hpp"
#include "geotandem/volume/io.hpp"
#include "page_cache.hpp"

namespace {

namespace fs = std::filesystem;
namespace gv = geotandem::volume;

#ifndef GEOTANDEM_BENCH_DATA
#define GEOTANDEM_BENCH_DATA "build/bench-data"
#endif

float formula(std::int64_t i, std::int64_t j, std::int64_t k) {
  return static_cast<float>((i * 7 + j * 13 + k * 3) % 1000) * 0.01f + static_cast<float>(k) * 1e-4f;
}

// A cube computed box by box, so that writing 2 GiB never holds it in memory.
class FormulaVolume final : public gv::Volume {
public:
  explicit FormulaVolume(gv::Index3 shape) { geometry_.shape = shape; }
  const gv::Geometry& geometry() const override { return geometry_; }
  std::string format() const override { return "formula"; }
  std::string source() const override { return "bench formula"; }

protected:
  void read_box(const gv::Box& box, std::span<float> out) const override {
    std::size_t n = 0;
    for (std::int64_t i = box.lo[0]; i < box.hi[0]; ++i)
      for (std::int64_t j = box.lo[1]; j < box.hi[1]; ++j)
        for (std::int64_t k = box.lo[2]; k < box.hi[2]; ++k)
          out[n++] = formula(i, j, k);
  }

private:
  gv::Geometry geometry_;
};

struct Options {
  std::string dir = GEOTANDEM_BENCH_DATA;
  gv::Index3 shape{1024, 1024, 512};
  int chunk = 64;
  int box = 128;
};

Options parse(int argc, char** argv) {
  Options o;
  auto number = [&](int& at) {
    if (at + 1 >= argc) throw geotandem::InvalidArgument(std::string("missing value after ") + argv[at]);
    return std::stoll(argv[++at]);
  };
  for (int a = 1; a < argc; ++a) {
    std::string arg = argv[a];
    if (arg == "--dir" && a + 1 < argc) {
      o.dir = argv[++a];
    } else if (arg == "--shape") {
      for (auto& n : o.shape)
        n = number(a);
    } else if (arg == "--chunk") {
      o.chunk = static_cast<int>(number(a));
    } else if (arg == "--box") {
      o.box = static_cast<int>(number(a));
    } else {
      throw geotandem::InvalidArgument("unknown argument '" + arg + "'", {},
                                       "usage: bench_box_read [--dir DIR] [--shape NI NJ NK] [--chunk C] [--box B]");
    }
  }
  return o;
}

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Reads every byte of every file of `path`; returns the byte count.
std::uint64_t read_raw(const fs::path& path) {
  std::vector<char> buffer(8 << 20);
  std::uint64_t total = 0;
  for (const fs::path& file : geotandem::bench::files_of(path)) {
    int fd = ::open(file.c_str(), O_RDONLY);
    if (fd < 0) throw geotandem::IoError("cannot open", {file.string()});
    for (ssize_t got; (got = ::read(fd, buffer.data(), buffer.size())) > 0;)
      total += static_cast<std::uint64_t>(got);
    ::close(fd);
  }
  return total;
}

// Reads the whole cube by boxes of `edge` (clipped), in C order of the boxes; `slab_depth` > 0
// reads slabs of that many whole inlines instead. Checks a few samples against the formula.
double read_all(const gv::Volume& cube, int edge, int slab_depth) {
  const gv::Index3 shape = cube.geometry().shape;
  const gv::Index3 step = slab_depth > 0 ? gv::Index3{slab_depth, shape[1], shape[2]} : gv::Index3{edge, edge, edge};
  std::vector<float> buffer;
  auto start = Clock::now();
  for (std::int64_t i = 0; i < shape[0]; i += step[0])
    for (std::int64_t j = 0; j < shape[1]; j += step[1])
      for (std::int64_t k = 0; k < shape[2]; k += step[2]) {
        gv::Box box =
            gv::Box{{i, j, k}, {i + step[0], j + step[1], k + step[2]}}.intersection(gv::Box::of_shape(shape));
        buffer.resize(box.count());
        cube.read(box, buffer);
        const gv::Index3 far{box.hi[0] - 1, box.hi[1] - 1, box.hi[2] - 1};
        if (buffer.front() != formula(i, j, k) || buffer.back() != formula(far[0], far[1], far[2]))
          throw geotandem::DataError("wrong samples in box " + box.to_string(), {cube.source()});
      }
  return seconds_since(start);
}

std::string rate(double bytes, double seconds) {
  char text[64];
  std::snprintf(text, sizeof text, "%8.1f MB/s (%6.2f s)", bytes / seconds / 1e6, seconds);
  return text;
}

void run(const Options& o, const std::string& extension) {
  const std::string name = "cube_" + std::to_string(o.shape[0]) + "x" + std::to_string(o.shape[1]) + "x" +
                           std::to_string(o.shape[2]) + "_c" + std::to_string(o.chunk) + extension;
  const fs::path path = fs::path(o.dir) / name;
  const double bytes = static_cast<double>(gv::Box::of_shape(o.shape).count()) * sizeof(float);
  bool reuse = false;
  if (fs::exists(path)) {
    try {
      reuse = gv::open_volume(path.string())->geometry().shape == o.shape;
    } catch (const geotandem::Error&) {
      reuse = false;
    }
  }
  std::string format = extension == ".nc" ? "netCDF-4" : "Zarr";
  if (reuse) {
    std::cout << std::left << std::setw(10) << format << "reusing " << path.string() << std::endl;
  } else {
    FormulaVolume source(o.shape);
    auto start = Clock::now();
    gv::write_volume(source, path.string(), {.chunk = o.chunk, .overwrite = true});
    std::cout << std::left << std::setw(10) << format << std::setw(24)
              << ("write, chunk " + std::to_string(o.chunk) + "^3") << "     " << rate(bytes, seconds_since(start))
              << std::endl;
  }
  const auto cube = gv::open_volume(path.string());
  format = cube->format();
  const std::string boxes = "boxes " + std::to_string(o.box) + "^3";
  const std::string slabs = "slabs of " + std::to_string(o.chunk) + " inlines";
  for (const auto& [label, edge, depth] : {std::tuple{boxes, o.box, 0}, std::tuple{slabs, 0, o.chunk}}) {
    bool cold = geotandem::bench::evict(path);
    double t_cold = read_all(*cube, edge, depth);
    double t_warm = read_all(*cube, edge, depth);
    std::cout << std::left << std::setw(10) << format << std::setw(24) << label << (cold ? "cold " : "evict failed ")
              << rate(bytes, t_cold) << "   warm " << rate(bytes, t_warm) << std::endl;
  }
  bool cold = geotandem::bench::evict(path);
  auto start = Clock::now();
  double raw_bytes = static_cast<double>(read_raw(path));
  std::cout << std::left << std::setw(10) << format << std::setw(24) << "raw bytes of the files"
            << (cold ? "cold " : "evict failed ") << rate(raw_bytes, seconds_since(start)) << std::endl;
}

} // namespace

int main(int argc, char** argv) {
  try {
    const Options o = parse(argc, argv);
    fs::create_directories(o.dir);
    const double mib = static_cast<double>(gv::Box::of_shape(o.shape).count()) * sizeof(float) / (1 << 20);
    std::cout << "bench_box_read: cube " << o.shape[0] << "x" << o.shape[1] << "x" << o.shape[2] << " float32 (" << mib
              << " MiB), chunk " << o.chunk << ", box " << o.box << ", data in " << o.dir << std::endl;
    for (const char* extension : {".nc", ".zarr"})
      run(o, extension);
    return 0;
  } catch (const geotandem::Error& error) {
    std::cerr << "bench_box_read: " << error.what() << std::endl;
    return error.exit_code();
  } catch (const std::exception& error) {
    std::cerr << "bench_box_read: " << error.what() << std::endl;
    return 1;
  }
}
