// Speed of the mesh part on surfaces of about a million triangles: topology check, component
// split, measures, anisotropy and sampled distances. Prints one line per figure.
//
//   mesh_bench [triangles_in_millions=1]

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <numeric>
#include <random>
#include <time.h>

#include "geotandem/mesh/measure.hpp"
#include "geotandem/mesh/quality.hpp"
#include "geotandem/mesh/topology.hpp"

using namespace geotandem;
using mesh::Point;
using mesh::SurfaceMesh;

namespace {

// A torus of nu x nv quads with a bumpy tube radius: 2 nu nv triangles.
SurfaceMesh bumpy_torus(int nu, int nv, double bump) {
  SurfaceMesh s;
  const double two_pi = 2.0 * std::numbers::pi;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double u = two_pi * i / nu, v = two_pi * j / nv;
      const double r = 20.0 * (1.0 + bump * std::sin(7 * u) * std::cos(5 * v));
      s.points.push_back({100 + (60 + r * std::cos(v)) * std::cos(u), 100 + (60 + r * std::cos(v)) * std::sin(u),
                          100 + r * std::sin(v)});
    }
  auto id = [&](int i, int j) { return static_cast<std::uint32_t>((i % nu) * nv + (j % nv)); };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      s.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      s.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return s;
}

// The same surface with vertices and triangles in random order (no memory locality at all).
SurfaceMesh shuffled(const SurfaceMesh& s) {
  std::mt19937 rng(1);
  std::vector<std::uint32_t> perm(s.points.size());
  std::iota(perm.begin(), perm.end(), 0u);
  std::shuffle(perm.begin(), perm.end(), rng);
  SurfaceMesh out;
  out.points.resize(s.points.size());
  for (std::size_t v = 0; v < s.points.size(); ++v)
    out.points[perm[v]] = s.points[v];
  for (const auto& t : s.triangles)
    out.triangles.push_back({perm[t[0]], perm[t[1]], perm[t[2]]});
  std::shuffle(out.triangles.begin(), out.triangles.end(), rng);
  return out;
}

// Process CPU time: every step is single-threaded, and the figure stays meaningful on a loaded
// machine.
double cpu_now() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

template <class Fn> double seconds(Fn&& fn) {
  const double t0 = cpu_now();
  fn();
  return cpu_now() - t0;
}

void line(const char* what, std::size_t triangles, double s) {
  std::printf("%-48s %9.1f ms cpu  %7.2f M triangles/s\n", what, 1e3 * s, static_cast<double>(triangles) / s / 1e6);
}

} // namespace

int main(int argc, char** argv) {
  const double millions = argc > 1 ? std::atof(argv[1]) : 1.0;
  const int nv = std::max(8, static_cast<int>(std::sqrt(millions * 1e6 / 4.0)));
  const int nu = 2 * nv;
  const SurfaceMesh s = bumpy_torus(nu, nv, 0.1);
  const SurfaceMesh r = shuffled(s);
  const SurfaceMesh coarse = bumpy_torus(nu / 4, nv / 4, 0.1);
  const std::size_t n = s.triangles.size();
  std::printf("surface: %zu triangles, %zu vertices (coarse copy %zu triangles)\n", n, s.points.size(),
              coarse.triangles.size());

  mesh::TopologyReport report;
  line("check_topology (storage order)", n, seconds([&] { report = mesh::check_topology(s); }));
  std::printf("  %s\n", report.summary().c_str());
  line("check_topology (shuffled)", n, seconds([&] { report = mesh::check_topology(r); }));
  std::size_t parts = 0;
  line("split_components", n, seconds([&] { parts = mesh::split_components(s).size(); }));
  std::printf("  %zu component(s)\n", parts);

  volume::Geometry g;
  g.shape = {400, 400, 400};
  g.affine.xi = 12.5;
  g.affine.yj = 25.0;
  mesh::ComponentStats stats;
  line("measure_component", n, seconds([&] { stats = mesh::measure_component(s, g); }));
  std::printf("  volume %.6g area %.6g azimuth %.2f elongation %.3f\n", stats.volume, stats.area, stats.azimuth,
              stats.elongation);
  double an = 0.0;
  line("anisotropy", n, seconds([&] { an = mesh::anisotropy(s); }));
  std::printf("  anisotropy %.4f\n", an);

  for (int samples : {0, 3}) {
    mesh::DistanceStats d;
    char what[96];
    std::snprintf(what, sizeof what, "one_sided_distance fine->coarse, %d/tri", samples);
    const double t = seconds([&] { d = mesh::one_sided_distance(s, coarse, samples); });
    line(what, n, t);
    std::printf("  %zu samples, %.2f M samples/s, max %.4g rms %.4g\n", d.samples,
                static_cast<double>(d.samples) / t / 1e6, d.max, d.rms);
  }
  {
    mesh::DistanceStats d;
    const double t = seconds([&] { d = mesh::one_sided_distance(coarse, s, 3); });
    line("one_sided_distance coarse->fine, 3/tri (grid of fine)", n, t);
    std::printf("  %zu samples, %.2f M samples/s, max %.4g\n", d.samples, static_cast<double>(d.samples) / t / 1e6,
                d.max);
  }
  return 0;
}
