// Attribute throughput on one core: each attribute computed on a generated cube (default 256^3),
// once as a single whole-cube box and once fused block by block (64^3 boxes, each read with its
// halo, as the extraction will read them). Prints M output voxels per second, and checks that both
// ways give the same samples.
//
// Usage: bench_attributes [size=256] [block=64] [only: run the attributes whose label contains it]

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <memory>
#include <string>
#include <vector>

#include "bench_args.hpp"
#include "geotandem/attributes/chaos.hpp"
#include "geotandem/attributes/envelope.hpp"
#include "geotandem/attributes/normalise.hpp"
#include "geotandem/attributes/product.hpp"
#include "geotandem/attributes/rms.hpp"
#include "geotandem/attributes/semblance.hpp"

namespace {

using namespace geotandem;
using attributes::VolumePtr;
using volume::Box;

double noise(std::int64_t i, std::int64_t j, std::int64_t k) {
  std::uint64_t x =
      (static_cast<std::uint64_t>(i) << 42) ^ (static_cast<std::uint64_t>(j) << 21) ^ static_cast<std::uint64_t>(k);
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  x ^= x >> 31;
  return static_cast<double>(x >> 11) / static_cast<double>(1ull << 52) - 1.0;
}

// Dipping layers plus noise, with a noisier, brighter lens in the middle.
std::shared_ptr<volume::MemoryVolume> make_input(std::int64_t n) {
  volume::Geometry g;
  g.shape = {n, n, n};
  std::vector<float> samples(g.sample_count());
  std::size_t s = 0;
  for (std::int64_t i = 0; i < n; ++i)
    for (std::int64_t j = 0; j < n; ++j)
      for (std::int64_t k = 0; k < n; ++k) {
        const double di = (i - n / 2.0) / (n / 4.0), dj = (j - n / 2.0) / (n / 4.0), dk = (k - n / 2.0) / (n / 8.0);
        const bool lens = di * di + dj * dj + dk * dk < 1.0;
        samples[s++] = static_cast<float>(std::cos(0.35 * k + 0.04 * i - 0.03 * j) * (lens ? 2.0 : 1.0) +
                                          noise(i, j, k) * (lens ? 1.5 : 0.2));
      }
  return std::make_shared<volume::MemoryVolume>(g, std::move(samples), "bench cube");
}

// CPU time of this (single-threaded) process: "per core" figures that hold on a busy machine.
double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

std::string only;

void run(const std::string& label, const volume::Volume& attribute, std::int64_t block) {
  if (label.find(only) == std::string::npos) return;
  const Box bounds = attribute.geometry().bounds();
  const double voxels = static_cast<double>(bounds.count());

  const double start = cpu_seconds();
  const std::vector<float> whole = attribute.read(bounds);
  const double whole_s = cpu_seconds() - start;

  std::size_t mismatches = 0;
  std::vector<float> part;
  double fused_compute = 0.0;
  for (std::int64_t i = 0; i < bounds.hi[0]; i += block)
    for (std::int64_t j = 0; j < bounds.hi[1]; j += block)
      for (std::int64_t k = 0; k < bounds.hi[2]; k += block) {
        const Box box = Box{{i, j, k}, {i + block, j + block, k + block}}.intersection(bounds);
        part.resize(box.count());
        const double t = cpu_seconds();
        attribute.read(box, part);
        fused_compute += cpu_seconds() - t;
        for (std::int64_t a = box.lo[0]; a < box.hi[0]; ++a)
          for (std::int64_t b = box.lo[1]; b < box.hi[1]; ++b)
            if (std::memcmp(&part[box.offset({a, b, box.lo[2]})], &whole[bounds.offset({a, b, box.lo[2]})],
                            static_cast<std::size_t>(box.size(2)) * sizeof(float)) != 0)
              ++mismatches;
      }
  std::printf("%-34s %9.2f %9.2f   %9.2f %9.2f   %s\n", label.c_str(), whole_s, voxels / whole_s / 1e6, fused_compute,
              voxels / fused_compute / 1e6, mismatches == 0 ? "identical" : "DIFFERENT");
}

} // namespace

int bench_main(int argc, char** argv) {
  const geotandem::bench::Args args(
      argc, argv, "bench_attributes [size=256] [block=64] [only: run the attributes whose label contains it]");
  const std::int64_t n = args.integer(1, 256, 1);
  const std::int64_t block = args.integer(2, 64, 1);
  only = args.text(3, only);
  double start = cpu_seconds();
  VolumePtr input = make_input(n);
  std::printf("input %lld^3 generated in %.2f s; blocks %lld^3; one thread, CPU seconds\n", static_cast<long long>(n),
              cpu_seconds() - start, static_cast<long long>(block));
  std::printf("%-34s %9s %9s   %9s %9s   %s\n", "attribute (halo)", "whole s", "Mvox/s", "fused s", "Mvox/s",
              "fused vs whole");

  auto halo_text = [](const attributes::Attribute& a) {
    const auto h = a.total_halo();
    return " (" + std::to_string(h[0]) + "," + std::to_string(h[1]) + "," + std::to_string(h[2]) + ")";
  };
  auto envelope = std::make_shared<attributes::Envelope>(input);
  auto rms = std::make_shared<attributes::Rms>(input);
  auto semblance = std::make_shared<attributes::Semblance>(input);
  auto chaos = std::make_shared<attributes::Chaos>(input);
  auto marfurt = std::make_shared<attributes::Chaos>(
      input, attributes::ChaosOptions{.formula = attributes::ChaosFormula::marfurt});
  auto normalised = std::make_shared<attributes::Normalise>(envelope);
  start = cpu_seconds();
  const double scale = normalised->scale();
  std::printf("normalise: 99th percentile of the envelope = %.4f, sampled in %.3f s (%zu boxes)\n", scale,
              cpu_seconds() - start, normalised->sample_boxes().size());
  auto product = std::make_shared<attributes::Product>(chaos, normalised);

  run("envelope" + halo_text(*envelope), *envelope, block);
  run("rms" + halo_text(*rms), *rms, block);
  run("semblance" + halo_text(*semblance), *semblance, block);
  run("chaos planarity" + halo_text(*chaos), *chaos, block);
  run("chaos marfurt" + halo_text(*marfurt), *marfurt, block);
  run("normalise(envelope)" + halo_text(*normalised), *normalised, block);
  run("chaos x normalise(envelope)" + halo_text(*product), *product, block);
  return 0;
}

int main(int argc, char** argv) {
  return geotandem::bench::guarded_main("bench_attributes", [&] { return bench_main(argc, argv); });
}
