// bench_volume_io: write and read throughput of the SEG-Y and raw formats.
//
//   bench_volume_io [NI NJ NK] [DIR]
//
// Generates a procedural cube (default 256 x 256 x 400 float32, 100 MiB) without holding it in
// memory, writes it as SEG-Y and raw into DIR (default: a fresh directory under the system's temp
// directory, removed at the end), then times box reads: the whole cube, 64^3 blocks tiling the
// cube, one inline, one crossline and one sample slice. The files were just written, so reads
// come mostly from the page cache: the figures measure the readers, not the disk. Reads go
// through open_volume, so they include the NaN check.
//
// Then opening an irregular survey: the SEG-Y file again without the traces of a corner (a tenth
// of the crosslines on half of the inlines), opened with the NaN fill policy. Its grid takes a
// pass over every trace header, which the manager makes once and hands to its workers
// (Volume::reopen_hint); the figures are that pass, from the page cache ("warm") and with the
// file's pages dropped first ("cold"), against an open given the hint.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <fstream>
#include <limits>

#include "bench_args.hpp"
#include "geotandem/volume/io.hpp"
#include "page_cache.hpp"

namespace fs = std::filesystem;
using namespace geotandem::volume;

namespace {

// Samples computed on demand, so that the generator costs little next to the I/O.
class Procedural final : public Volume {
public:
  explicit Procedural(Geometry g) : geometry_(std::move(g)) {}
  const Geometry& geometry() const override { return geometry_; }
  std::string format() const override { return "procedural"; }
  std::string source() const override { return "procedural benchmark cube"; }

protected:
  void read_box(const Box& box, std::span<float> out) const override {
    std::size_t n = 0;
    for (std::int64_t i = box.lo[0]; i < box.hi[0]; ++i)
      for (std::int64_t j = box.lo[1]; j < box.hi[1]; ++j)
        for (std::int64_t k = box.lo[2]; k < box.hi[2]; ++k)
          out[n++] = static_cast<float>((i * 7 + j * 13 + k * 3) % 1024) * 0.25f;
  }

private:
  Geometry geometry_;
};

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double mib(std::size_t samples) {
  return static_cast<double>(samples) * sizeof(float) / (1024.0 * 1024.0);
}

void report(const char* format, const char* what, std::size_t samples, double seconds) {
  std::printf("%-6s %-26s %10.1f MiB %9.3f s %9.1f MiB/s\n", format, what, mib(samples), seconds,
              mib(samples) / seconds);
}

void time_reads(const char* name, const Volume& volume) {
  const Geometry& g = volume.geometry();
  const Index3 s = g.shape;
  // One buffer for every read, allocated and touched before the clock starts: the figures are
  // the readers', not the allocator's.
  std::vector<float> buffer(g.sample_count(), 0.0f);
  auto timed = [&](const char* what, const std::vector<Box>& boxes) {
    std::size_t samples = 0;
    double checksum = 0;
    auto start = std::chrono::steady_clock::now();
    for (const Box& box : boxes) {
      std::span<float> values(buffer.data(), box.count());
      volume.read(box, values);
      samples += values.size();
      checksum += values.front();
    }
    const double seconds = seconds_since(start);
    report(name, what, samples, seconds);
    if (!std::isfinite(checksum)) std::printf("(checksum %g)\n", checksum);
  };
  timed("whole cube", {g.bounds()});
  std::vector<Box> blocks;
  for (std::int64_t i = 0; i < s[0]; i += 64)
    for (std::int64_t j = 0; j < s[1]; j += 64)
      for (std::int64_t k = 0; k < s[2]; k += 64)
        blocks.push_back(Box{{i, j, k}, {i + 64, j + 64, k + 64}}.intersection(g.bounds()));
  timed("64^3 blocks", blocks);
  timed("one inline", {Box{{s[0] / 2, 0, 0}, {s[0] / 2 + 1, s[1], s[2]}}});
  timed("one crossline", {Box{{0, s[1] / 2, 0}, {s[0], s[1] / 2 + 1, s[2]}}});
  timed("one sample slice", {Box{{0, 0, s[2] / 2}, {s[0], s[1], s[2] / 2 + 1}}});
}

// `full` (written by geotandem: 4-byte samples, no extended headers) copied to `out` without
// the traces of inlines i < ni / 2 and crosslines j < nj / 10; returns the traces left.
std::int64_t write_irregular(const std::string& full, const std::string& out, const Index3& shape) {
  std::ifstream in(full, std::ios::binary);
  std::ofstream to(out, std::ios::binary | std::ios::trunc);
  std::vector<char> buffer(3600);
  in.read(buffer.data(), 3600);
  to.write(buffer.data(), 3600);
  buffer.resize(static_cast<std::size_t>(240 + 4 * shape[2]));
  std::int64_t kept = 0;
  for (std::int64_t i = 0; i < shape[0]; ++i)
    for (std::int64_t j = 0; j < shape[1]; ++j) {
      in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
      if (i < shape[0] / 2 && j < shape[1] / 10) continue;
      to.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
      ++kept;
    }
  if (!in || !to) throw std::runtime_error("cannot copy " + full + " to " + out);
  return kept;
}

void time_reopen(const std::string& full, const Index3& shape) {
  const std::string path = full + ".irregular.segy";
  const std::int64_t traces = write_irregular(full, path, shape);
  OpenOptions fill;
  fill.nan_policy = NanPolicy::fill;
  fill.fill_value = std::numeric_limits<float>::quiet_NaN();
  const std::string hint = open_volume(path, fill)->reopen_hint();
  OpenOptions hinted = fill;
  hinted.reopen_hint = hint;
  std::printf("irregular survey: %lld of %lld traces; the grid handed on is %zu bytes of text\n",
              static_cast<long long>(traces), static_cast<long long>(shape[0] * shape[1]), hint.size());
  for (const bool cold : {true, false})
    for (const bool with_hint : {false, true}) {
      double best = std::numeric_limits<double>::infinity();
      bool evicted = true;
      for (int run = 0; run < 3; ++run) {
        if (cold) evicted = geotandem::bench::evict(path) && evicted;
        const auto start = std::chrono::steady_clock::now();
        const auto volume = open_volume(path, with_hint ? hinted : fill);
        best = std::min(best, seconds_since(start));
      }
      std::printf("open   %-26s %9.3f s (best of 3)%s\n", with_hint ? "given the grid" : "scanning every header", best,
                  cold ? (evicted ? ", cold" : ", evict failed: warm") : ", warm");
    }
  std::filesystem::remove(path);
}

} // namespace

int bench_main(int argc, char** argv) {
  const geotandem::bench::Args args(argc, argv, "bench_volume_io [NI NJ NK] [DIR]");
  if (args.size() != 0 && args.size() != 3 && args.size() != 4)
    args.fail(args.size(), "is out of place: give NI NJ NK [DIR], or nothing");
  Geometry g;
  g.shape = {args.integer(1, 256, 1), args.integer(2, 256, 1), args.integer(3, 400, 1)};
  const bool own_dir = !args.has(4);
  const fs::path dir = own_dir ? fs::temp_directory_path() /
                                     ("geotandem-bench-volume-io-" +
                                      std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()))
                               : fs::path(args.text(4, ""));
  fs::create_directories(dir);
  const Procedural cube(g);
  std::printf("cube %lld x %lld x %lld float32 (%.1f MiB) in %s\n", static_cast<long long>(g.shape[0]),
              static_cast<long long>(g.shape[1]), static_cast<long long>(g.shape[2]), mib(g.sample_count()),
              dir.c_str());

  WriteOptions overwrite;
  overwrite.overwrite = true;
  for (const char* name : {"raw", "segy"}) {
    const std::string path = (dir / (std::string("cube.") + name)).string();
    auto start = std::chrono::steady_clock::now();
    write_volume(cube, path, overwrite);
    report(name, "write", g.sample_count(), seconds_since(start));
    time_reads(name, *open_volume(path));
    if (std::string(name) == "segy") time_reopen(path, g.shape);
  }
  if (own_dir) fs::remove_all(dir);
  return 0;
}

int main(int argc, char** argv) {
  return geotandem::bench::guarded_main("bench_volume_io", [&] { return bench_main(argc, argv); });
}
