// The bench's own noisy cube (see noisy_cube.hpp). Nothing here comes from geotandem: the random
// numbers are splitmix64, the noise a hashed lattice interpolated with smoothstep weights.

#include "flying_edges/noisy_cube.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace geotandem::bench {
namespace {

static_assert(std::endian::native == std::endian::little, "the raw cube is written as the host's float32");

std::uint64_t mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

class Random {
public:
  explicit Random(std::uint64_t seed) : state_(mix(seed)) {}
  double uniform(double lo, double hi) {
    state_ = mix(state_);
    return lo + (hi - lo) * static_cast<double>(state_ >> 11) * 0x1.0p-53;
  }

private:
  std::uint64_t state_;
};

// One octave of value noise with an integer period: lattice values in [-1, 1] hashed from the
// seed, interpolated with smoothstep weights. Computed a (i, j) row at a time: the lattice is first
// interpolated in i and j for every lattice k, then each sample is one blend along k.
class ValueNoise {
public:
  ValueNoise(std::int64_t edge, std::int64_t period, std::uint64_t seed)
      : period_(period), cells_(edge / period + 2), lattice_(static_cast<std::size_t>(cells_ * cells_ * cells_)),
        row_(static_cast<std::size_t>(cells_)) {
    for (std::size_t n = 0; n < lattice_.size(); ++n)
      lattice_[n] = static_cast<float>(static_cast<double>(mix(seed ^ mix(n)) >> 11) * 0x1.0p-52 - 1.0);
  }

  // Fills the row (i, j); sample(k) then gives the noise at (i, j, k).
  void start_row(std::int64_t i, std::int64_t j) {
    const std::int64_t ci = i / period_, cj = j / period_;
    const double wi = weight(i), wj = weight(j);
    for (std::int64_t ck = 0; ck < cells_; ++ck) {
      auto at = [&](std::int64_t a, std::int64_t b) {
        return static_cast<double>(lattice_[static_cast<std::size_t>((a * cells_ + b) * cells_ + ck)]);
      };
      const double lo = at(ci, cj) + wj * (at(ci, cj + 1) - at(ci, cj));
      const double hi = at(ci + 1, cj) + wj * (at(ci + 1, cj + 1) - at(ci + 1, cj));
      row_[static_cast<std::size_t>(ck)] = lo + wi * (hi - lo);
    }
  }
  double sample(std::int64_t k) const {
    const auto ck = static_cast<std::size_t>(k / period_);
    return row_[ck] + weight(k) * (row_[ck + 1] - row_[ck]);
  }

private:
  double weight(std::int64_t t) const {
    const double f = static_cast<double>(t % period_) / static_cast<double>(period_);
    return f * f * (3.0 - 2.0 * f);
  }

  std::int64_t period_;
  std::int64_t cells_;
  std::vector<float> lattice_;
  std::vector<double> row_;
};

struct Blob {
  std::array<double, 3> centre;
  std::array<std::array<double, 3>, 3> axes; // rows: unit axes divided by their radius
  double reach;                              // the largest radius
  double weight;
};

Blob random_blob(Random& random, double edge, double smallest, double largest) {
  Blob b{};
  for (double& c : b.centre)
    c = random.uniform(0.0, edge);
  // A uniform rotation from a random unit quaternion (rejection from the unit ball).
  double q[4];
  double n2 = 0.0;
  do {
    n2 = 0.0;
    for (double& v : q) {
      v = random.uniform(-1.0, 1.0);
      n2 += v * v;
    }
  } while (n2 > 1.0 || n2 < 1e-6);
  const double s = 1.0 / std::sqrt(n2);
  const double w = q[0] * s, x = q[1] * s, y = q[2] * s, z = q[3] * s;
  const double rotation[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
                                 {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
                                 {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}};
  b.reach = 0.0;
  for (int a = 0; a < 3; ++a) {
    const double radius = random.uniform(smallest, largest);
    b.reach = std::max(b.reach, radius);
    for (int c = 0; c < 3; ++c)
      b.axes[static_cast<std::size_t>(a)][static_cast<std::size_t>(c)] = rotation[a][c] / radius;
  }
  b.weight = random.uniform(0.8, 1.2);
  return b;
}

} // namespace

std::vector<float> make_noisy_cube(const NoisyCubeOptions& options) {
  const std::int64_t n = options.edge;
  const auto size = static_cast<std::size_t>(n * n * n);
  std::vector<float> cube(size);
  ValueNoise coarse(n, 8, mix(options.seed) ^ 1);
  ValueNoise fine(n, 3, mix(options.seed) ^ 2);
  for (std::int64_t i = 0; i < n; ++i)
    for (std::int64_t j = 0; j < n; ++j) {
      coarse.start_row(i, j);
      fine.start_row(i, j);
      float* row = cube.data() + (i * n + j) * n;
      for (std::int64_t k = 0; k < n; ++k)
        row[k] = static_cast<float>(options.noise_coarse * coarse.sample(k) + options.noise_fine * fine.sample(k));
    }

  Random random(options.seed);
  const double scale = static_cast<double>(n) / 512.0;
  const auto blobs = std::max<std::int64_t>(1, std::llround(options.blobs_per_512 * scale * scale * scale));
  for (std::int64_t b = 0; b < blobs; ++b) {
    const Blob blob = random_blob(random, static_cast<double>(n), options.smallest_radius, options.largest_radius);
    std::int64_t lo[3], hi[3];
    for (std::size_t a = 0; a < 3; ++a) {
      lo[a] = std::max<std::int64_t>(0, static_cast<std::int64_t>(std::floor(blob.centre[a] - blob.reach)));
      hi[a] = std::min<std::int64_t>(n - 1, static_cast<std::int64_t>(std::ceil(blob.centre[a] + blob.reach)));
    }
    for (std::int64_t i = lo[0]; i <= hi[0]; ++i)
      for (std::int64_t j = lo[1]; j <= hi[1]; ++j)
        for (std::int64_t k = lo[2]; k <= hi[2]; ++k) {
          const double d[3] = {static_cast<double>(i) - blob.centre[0], static_cast<double>(j) - blob.centre[1],
                               static_cast<double>(k) - blob.centre[2]};
          double r2 = 0.0;
          for (const auto& axis : blob.axes) {
            const double t = axis[0] * d[0] + axis[1] * d[1] + axis[2] * d[2];
            r2 += t * t;
          }
          if (r2 >= 1.0) continue;
          const double u = 1.0 - r2;
          cube[static_cast<std::size_t>((i * n + j) * n + k)] += static_cast<float>(blob.weight * u * u);
        }
  }
  return cube;
}

void write_raw_cube(const std::vector<float>& samples, std::int64_t edge, const std::filesystem::path& path) {
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(samples.data()),
              static_cast<std::streamsize>(samples.size() * sizeof(float)));
    if (!out) throw std::runtime_error("cannot write the cube " + path.string());
  }
  const std::string e = std::to_string(edge);
  std::ofstream json(path.string() + ".json", std::ios::trunc);
  json << R"({"format": "geotandem-raw", "version": 1, "dtype": "float32", "byte_order": "little", "order": "C",)"
       << "\n"
       << R"( "axes": ["inline", "crossline", "sample"], "shape": [)" << e << ", " << e << ", " << e << "],\n"
       << R"( "geometry": {"inline0": 0, "inline_step": 1, "crossline0": 0, "crossline_step": 1,)"
       << R"( "z0": 0, "dz": 1, "z_unit": "m",)"
       << "\n"
       << R"(  "affine": {"x0": 0.0, "xi": 1.0, "xj": 0.0, "y0": 0.0, "yi": 0.0, "yj": 1.0}}})"
       << "\n";
  if (!json) throw std::runtime_error("cannot write the sidecar " + path.string() + ".json");
}

std::unique_ptr<float[]> read_raw_cube(const std::filesystem::path& path, std::int64_t edge) {
  const auto bytes = static_cast<std::size_t>(edge * edge * edge) * sizeof(float);
  std::unique_ptr<float[]> samples(new float[bytes / sizeof(float)]); // not value-initialised: no zeroing pass
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw std::runtime_error("cannot open " + path.string() + ": " + std::strerror(errno));
  std::size_t done = 0;
  while (done < bytes) {
    const ssize_t n = ::read(fd, reinterpret_cast<char*>(samples.get()) + done, bytes - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    done += static_cast<std::size_t>(n);
  }
  char extra = 0;
  const bool longer = done == bytes && ::read(fd, &extra, 1) > 0;
  ::close(fd);
  if (done != bytes || longer)
    throw std::runtime_error("cannot read " + path.string() + " as a " + std::to_string(edge) + "^3 float32 cube");
  return samples;
}

} // namespace geotandem::bench
