// Generation throughput of the synthetic cubes: a cube computed box by box on one thread, as a
// block-parallel consumer would ask for it. Prints M samples/s per core (thread CPU time) and wall.
//
//   bench_synth_throughput [EDGE [BOX [SEED]]]     defaults: 256 64 1

#include <time.h>

#include <cmath>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>

#include "bench_args.hpp"
#include "geotandem/synth/synthetic.hpp"

namespace {

double thread_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

struct Timing {
  double cpu, wall;
};

Timing timed(const std::function<void()>& f) {
  const double c0 = thread_seconds();
  const auto w0 = std::chrono::steady_clock::now();
  f();
  return {thread_seconds() - c0, std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count()};
}

void run(const char* label, const std::function<std::unique_ptr<geotandem::synth::SyntheticCube>()>& make,
         std::int64_t box_edge) {
  std::unique_ptr<geotandem::synth::SyntheticCube> cube;
  const Timing layout = timed([&] { cube = make(); });
  const auto shape = cube->geometry().shape;
  double checksum = 0.0;
  std::vector<float> buffer;
  const Timing read = timed([&] {
    for (std::int64_t i = 0; i < shape[0]; i += box_edge)
      for (std::int64_t j = 0; j < shape[1]; j += box_edge)
        for (std::int64_t k = 0; k < shape[2]; k += box_edge) {
          const geotandem::volume::Box box{
              {i, j, k},
              {std::min(i + box_edge, shape[0]), std::min(j + box_edge, shape[1]), std::min(k + box_edge, shape[2])}};
          buffer.resize(box.count());
          cube->read(box, buffer);
          checksum += buffer[buffer.size() / 2];
        }
  });
  const double samples = static_cast<double>(cube->geometry().sample_count()) / 1e6;
  std::printf("%-9s %lldx%lldx%lld by %lld^3 boxes: %6.2f M samples/s per core (%.2f s CPU, %.2f s wall); "
              "layout %.3f s CPU; %zu bodies, %zu bubbles (checksum %.3f)\n",
              label, static_cast<long long>(shape[0]), static_cast<long long>(shape[1]),
              static_cast<long long>(shape[2]), static_cast<long long>(box_edge), samples / read.cpu, read.cpu,
              read.wall, layout.cpu, cube->truth().bodies.size(), cube->truth().bubble_count, checksum);
}

} // namespace

int bench_main(int argc, char** argv) {
  const geotandem::bench::Args args(argc, argv, "bench_synth_throughput [edge=256] [box=64] [seed=1]");
  const std::int64_t edge = args.integer(1, 256, 1);
  const std::int64_t box = args.integer(2, 64, 1);
  const auto seed = static_cast<std::uint64_t>(args.integer(3, 1, 0));
  run(
      "analytic",
      [&] {
        geotandem::synth::AnalyticOptions o;
        o.shape = {edge, edge, edge};
        o.seed = seed;
        return geotandem::synth::make_analytic(o);
      },
      box);
  run(
      "seismic",
      [&] {
        geotandem::synth::SeismicOptions o;
        o.shape = {edge, edge, edge};
        o.seed = seed;
        return geotandem::synth::make_seismic(o);
      },
      box);
  run(
      "seismic0",
      [&] { // no noise: the cost of the signal alone
        geotandem::synth::SeismicOptions o;
        o.shape = {edge, edge, edge};
        o.seed = seed;
        o.snr = HUGE_VAL;
        return geotandem::synth::make_seismic(o);
      },
      box);
  return 0;
}

int main(int argc, char** argv) {
  return geotandem::bench::guarded_main("bench_synth_throughput", [&] { return bench_main(argc, argv); });
}
