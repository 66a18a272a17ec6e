#pragma once
// The noisy cube of bench_flying_edges_meshopt, made by its own generator so that the comparison
// does not rest on geotandem's synthetic module: a sum of randomly placed and rotated ellipsoidal
// blobs, (1 - r^2)^2 inside each, plus two octaves of hashed value noise, all from one seed. The
// isosurface at 0.5 is a set of rough bodies with small bubbles along them.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace geotandem::bench {

struct NoisyCubeOptions {
  std::int64_t edge = 512;    // samples along each axis
  std::uint64_t seed = 1;     // the same seed gives the same bits on any machine
  double blobs_per_512 = 160; // blob count for a 512^3 cube, scaled with the volume
  double smallest_radius = 8; // blob radii (each of the three axes) drawn in [smallest, largest]
  double largest_radius = 40; // samples: fixed, so a cube of 8 times the volume has 8 times the bodies
  double noise_coarse = 0.25; // amplitude of the value noise of period 8 samples
  double noise_fine = 0.15;   // amplitude of the value noise of period 3 samples
};

// Samples in C order [i][j][k] (k fastest), the order of geotandem's raw cubes: index
// (i * edge + j) * edge + k.
std::vector<float> make_noisy_cube(const NoisyCubeOptions& options);

// Writes `samples` as a geotandem raw cube: `path` (little-endian float32) and `path`.json, the
// sidecar, written last. The geometry puts sample (i, j, k) at world (x, y, z) = (i, j, k):
// inline and crossline steps 1 m, samples 1 m apart in depth from 0. Throws std::runtime_error when
// a file cannot be written.
void write_raw_cube(const std::vector<float>& samples, std::int64_t edge, const std::filesystem::path& path);

// Reads back the samples of a raw cube written by write_raw_cube, as the other route would: into
// memory that is not zeroed first, with read(2) (the bench times it). Throws std::runtime_error when
// the file is missing or of the wrong size.
std::unique_ptr<float[]> read_raw_cube(const std::filesystem::path& path, std::int64_t edge);

} // namespace geotandem::bench
