// Triangle quality against the isotropy weight alpha (the seed's figure 12): anisotropy of the
// simplified surface for alpha = 0, 0.1, ..., 1 on one block covering an analytic synthetic cube,
// with the distances to the full-resolution marching-cubes surface (one-sided both ways: the
// Hausdorff distance, and the pooled RMS) and the share of triangles whose smallest angle is under
// 10 degrees; anisotropy and small angles also over the bodies alone (bubbles left out). With
// geotandem/tandem/blocks.hpp (extract_blocks) the same for 8 blocks (2 x 2 x 2 leaves, merged) with and without the
// extended time lag; without it the bench says so.
//
//   bench_tandem_quality [N=128] [--svg PATH=tandem_quality.svg] [--e0 X=0.5] [--seed S=1]
//                        [--no-guarantee]   (without the E0 guarantee, for comparison)
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench_args.hpp"
#include "geotandem/mesh/component.hpp"
#include "geotandem/mesh/quality.hpp"
#include "geotandem/synth/synthetic.hpp"
#include "geotandem/tandem/marching_cubes.hpp"
#include "geotandem/tandem/tandem.hpp"
#include "geotandem/volume/volume.hpp"

#if __has_include("geotandem/tandem/blocks.hpp")
#include "geotandem/tandem/blocks.hpp"
#define GEOTANDEM_BENCH_HAVE_BLOCKS 1
#endif

using namespace geotandem;

namespace {

void append(mesh::SurfaceMesh& to, const mesh::SurfaceMesh& from) {
  const auto base = static_cast<std::uint32_t>(to.points.size());
  to.points.insert(to.points.end(), from.points.begin(), from.points.end());
  for (const auto& t : from.triangles)
    to.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
}

// Gathers every component into one surface, and the bodies alone (without the bubbles: closed
// components enclosing less than the cube's bubble threshold) into another. Bubbles are a few
// octahedra whose shape alpha hardly changes; in the analytic cubes they hold about half of the
// output triangles and would otherwise dominate the mean.
class Collect final : public mesh::ComponentSink {
public:
  explicit Collect(double bubble_threshold) : bubble_threshold_(bubble_threshold) {}
  void commit(const mesh::Component& c) override {
    append(all, c.surface);
    ++count;
    if (c.stats.closed && std::abs(mesh::enclosed_volume(c.surface)) < bubble_threshold_) return;
    append(bodies, c.surface);
  }
  mesh::SurfaceMesh all, bodies;
  std::uint64_t count = 0;

private:
  double bubble_threshold_;
};

struct Point {
  double alpha = 0, anisotropy = 0, hausdorff = 0, rms = 0, small_angles = 0;
  double body_anisotropy = 0, body_small_angles = 0;
  std::uint64_t triangles = 0, components = 0;
};

struct Curve {
  std::string label;
  const char* colour;
  std::vector<Point> points;
};

Point measure(const Collect& sink, const mesh::SurfaceMesh& full, double alpha) {
  const mesh::SurfaceMesh& simplified = sink.all;
  Point p;
  p.alpha = alpha;
  p.anisotropy = mesh::anisotropy(simplified);
  p.body_anisotropy = mesh::anisotropy(sink.bodies);
  p.body_small_angles = mesh::small_angle_share(sink.bodies, 10.0);
  const mesh::DistanceStats d = mesh::hausdorff_distance(simplified, full);
  p.hausdorff = d.max;
  p.rms = d.rms;
  p.small_angles = mesh::small_angle_share(simplified, 10.0);
  p.triangles = simplified.triangle_count();
  p.components = sink.count;
  return p;
}

std::string fmt(const char* format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

void write_svg(const std::string& path, const std::vector<Curve>& curves, const std::string& title,
               const std::string& note) {
  const double W = 760, H = 500, left = 80, right = 230, top = 50, bottom = 80;
  const double pw = W - left - right, ph = H - top - bottom;
  double lo = 1.0, hi = 0.0;
  for (const Curve& c : curves)
    for (const Point& p : c.points) {
      lo = std::min({lo, p.anisotropy, p.body_anisotropy});
      hi = std::max({hi, p.anisotropy, p.body_anisotropy});
    }
  // y range: a margin of 0.01, rounded outwards to the tick step, at least 0.1 wide.
  const double y_step = hi - lo > 0.2 ? 0.05 : 0.02;
  lo = std::max(0.0, std::floor((lo - 0.01) / y_step) * y_step);
  hi = std::ceil((hi + 0.01) / y_step) * y_step;
  if (hi - lo < 0.1) hi = lo + 0.1;
  auto X = [&](double a) { return left + pw * a; };
  auto Y = [&](double v) { return top + ph * (1.0 - (v - lo) / (hi - lo)); };
  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H
      << "\" font-family=\"sans-serif\" font-size=\"13\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      << "<text x=\"" << left + pw / 2 << "\" y=\"28\" text-anchor=\"middle\" font-size=\"16\">" << title
      << "</text>\n";
  for (double v = lo; v <= hi + 1e-9; v += y_step)
    svg << "<line x1=\"" << left << "\" x2=\"" << left + pw << "\" y1=\"" << Y(v) << "\" y2=\"" << Y(v)
        << "\" stroke=\"#ddd\"/>\n<text x=\"" << left - 8 << "\" y=\"" << Y(v) + 4 << "\" text-anchor=\"end\">"
        << fmt("%.2f", v) << "</text>\n";
  for (int a = 0; a <= 10; ++a)
    svg << "<line x1=\"" << X(a / 10.0) << "\" x2=\"" << X(a / 10.0) << "\" y1=\"" << top << "\" y2=\"" << top + ph
        << "\" stroke=\"#eee\"/>\n<text x=\"" << X(a / 10.0) << "\" y=\"" << top + ph + 18
        << "\" text-anchor=\"middle\">" << fmt("%.1f", a / 10.0) << "</text>\n";
  svg << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << pw << "\" height=\"" << ph
      << "\" fill=\"none\" stroke=\"black\"/>\n<text x=\"" << left + pw / 2 << "\" y=\"" << top + ph + 42
      << "\" text-anchor=\"middle\">isotropy weight \xCE\xB1</text>\n<text transform=\"translate(22," << top + ph / 2
      << ") rotate(-90)\" text-anchor=\"middle\">anisotropy (1 \xE2\x88\x92 mean \xCF\x81)</text>\n";
  if (!note.empty())
    svg << "<text x=\"" << left << "\" y=\"" << H - 12 << "\" font-size=\"11\" fill=\"#555\">" << note << "</text>\n";
  for (std::size_t c = 0; c < curves.size(); ++c) {
    svg << "<polyline fill=\"none\" stroke=\"" << curves[c].colour << "\" stroke-width=\"2\" points=\"";
    for (const Point& p : curves[c].points)
      svg << fmt("%.1f", X(p.alpha)) << "," << fmt("%.1f", Y(p.anisotropy)) << " ";
    svg << "\"/>\n";
    for (const Point& p : curves[c].points)
      svg << "<circle cx=\"" << fmt("%.1f", X(p.alpha)) << "\" cy=\"" << fmt("%.1f", Y(p.anisotropy))
          << "\" r=\"3\" fill=\"" << curves[c].colour << "\"/>\n";
    svg << "<polyline fill=\"none\" stroke=\"" << curves[c].colour
        << "\" stroke-width=\"2\" stroke-dasharray=\"6,4\" points=\"";
    for (const Point& p : curves[c].points)
      svg << fmt("%.1f", X(p.alpha)) << "," << fmt("%.1f", Y(p.body_anisotropy)) << " ";
    svg << "\"/>\n";
    const double ly = top + 20 + 28 * static_cast<double>(c);
    svg << "<line x1=\"" << left + pw + 15 << "\" x2=\"" << left + pw + 45 << "\" y1=\"" << ly << "\" y2=\"" << ly
        << "\" stroke=\"" << curves[c].colour << "\" stroke-width=\"2\"/>\n<text x=\"" << left + pw + 52 << "\" y=\""
        << ly + 4 << "\">" << curves[c].label << "</text>\n";
  }
  const double ky = top + 20 + 28 * static_cast<double>(curves.size()) + 10;
  svg << "<line x1=\"" << left + pw + 15 << "\" x2=\"" << left + pw + 45 << "\" y1=\"" << ky << "\" y2=\"" << ky
      << "\" stroke=\"#555\" stroke-width=\"2\"/>\n<text x=\"" << left + pw + 52 << "\" y=\"" << ky + 4
      << "\" font-size=\"12\">all components</text>\n<line x1=\"" << left + pw + 15 << "\" x2=\"" << left + pw + 45
      << "\" y1=\"" << ky + 22 << "\" y2=\"" << ky + 22
      << "\" stroke=\"#555\" stroke-width=\"2\" stroke-dasharray=\"6,4\"/>\n<text x=\"" << left + pw + 52 << "\" y=\""
      << ky + 26 << "\" font-size=\"12\">bodies (no bubbles)</text>\n";
  svg << "</svg>\n";
  std::ofstream out(path);
  out << svg.str();
  if (!out) throw std::runtime_error("cannot write " + path);
}

} // namespace

int main(int argc, char** argv) {
  std::int64_t n = 128;
  std::string svg_path = "tandem_quality.svg";
  double e0 = 0.5;
  bool guarantee = true;
  synth::AnalyticOptions cube_options;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    const bool has_value = a + 1 < argc;
    if (arg == "--svg" && has_value) {
      svg_path = argv[++a];
    } else if (arg == "--e0" && has_value) {
      e0 = std::atof(argv[++a]);
    } else if (arg == "--no-guarantee") {
      guarantee = false; // the seed's algorithm: eps_0 <= E0 only
    } else if (arg == "--seed" && has_value) {
      cube_options.seed = std::strtoull(argv[++a], nullptr, 10);
    } else if (std::int64_t edge = 0; geotandem::bench::to_integer(arg, 2, edge)) {
      n = edge;
    } else {
      std::fprintf(arg == "--help" ? stdout : stderr,
                   "usage: %s [N=128] [--svg PATH] [--e0 X] [--seed S] [--no-guarantee]\n", argv[0]);
      return arg == "--help" ? 0 : 2;
    }
  }
  try {
    cube_options.shape = {n, n, n};
    const auto synth_cube = synth::make_analytic(cube_options);
    const auto cube = volume::MemoryVolume::copy_of(*synth_cube);
    const volume::Box cells = tandem::cube_cells(cube->geometry().shape);
    const float iso = static_cast<float>(synth::analytic_iso);
    const double bubble_threshold = synth_cube->truth().bubble_volume_threshold_voxels;
    const mesh::SurfaceMesh full = tandem::extract_surface(*cube, cells, {iso, 0});
    std::printf("analytic synthetic cube %lld^3 (seed %llu), iso 0.5, E0 %.2f voxel, axis 0\n"
                "full-resolution marching cubes: %zu triangles, anisotropy %.4f, small angles (< 10 deg) %.2f %%\n",
                static_cast<long long>(n), static_cast<unsigned long long>(cube_options.seed), e0,
                full.triangle_count(), mesh::anisotropy(full), 100.0 * mesh::small_angle_share(full, 10.0));

    std::vector<Curve> curves;
    curves.push_back({"1 block", "#1f77b4", {}});
#ifdef GEOTANDEM_BENCH_HAVE_BLOCKS
    // 2 x 2 x 2 leaves: the leaf size is half the cells per axis, rounded up.
    const std::int64_t leaf = n / 2; // n - 1 cells per axis: half of them, rounded up
    curves.push_back({"8 blocks, extended lag", "#2ca02c", {}});
    curves.push_back({"8 blocks, no ext. lag", "#d62728", {}});
    const std::string note;
#else
    const std::string note = "8-block curves await geotandem/tandem/blocks.hpp (extract_blocks)";
#endif
    for (int step = 0; step <= 10; ++step) {
      const double alpha = step / 10.0;
      tandem::TandemOptions options;
      options.iso = iso;
      options.simplify.max_error = e0;
      options.simplify.isotropy = alpha;
      options.simplify.guarantee_distance = guarantee;
      {
        Collect sink(bubble_threshold);
        tandem::extract_block(*cube, cells, options, &sink);
        curves[0].points.push_back(measure(sink, full, alpha));
      }
#ifdef GEOTANDEM_BENCH_HAVE_BLOCKS
      for (int lag = 0; lag < 2; ++lag) {
        options.simplify.extended_time_lag = lag == 0;
        Collect sink(bubble_threshold);
        const tandem::BlocksStats stats = tandem::extract_blocks(*cube, cells, leaf, options, &sink);
        if (stats.leaves != 8) std::fprintf(stderr, "warning: %zu leaves instead of 8\n", stats.leaves);
        curves[static_cast<std::size_t>(1 + lag)].points.push_back(measure(sink, full, alpha));
      }
#endif
      std::fprintf(stderr, "  alpha %.1f done\n", alpha);
    }
    std::printf("\n%-24s %5s %10s %7s %11s %10s %9s %12s %11s %12s\n", "route", "alpha", "triangles", "comps",
                "anisotropy", "hausdorff", "rms", "angles<10deg", "body-aniso", "body-<10deg");
    for (const Curve& c : curves)
      for (const Point& p : c.points)
        std::printf("%-24s %5.1f %10llu %7llu %11.4f %10.3f %9.3f %11.2f%% %11.4f %11.2f%%\n", c.label.c_str(), p.alpha,
                    static_cast<unsigned long long>(p.triangles), static_cast<unsigned long long>(p.components),
                    p.anisotropy, p.hausdorff, p.rms, 100.0 * p.small_angles, p.body_anisotropy,
                    100.0 * p.body_small_angles);
    std::printf("(distances in voxels to the full-resolution surface; hausdorff = max of both one-sided maxima, rms "
                "pooled over both directions)\n");
    if (!note.empty()) std::printf("note: %s\n", note.c_str());
    write_svg(svg_path, curves,
              "Anisotropy against \xCE\xB1, analytic cube " + std::to_string(n) + "\xC2\xB3, E0 " + fmt("%.2g", e0),
              note);
    std::printf("plot: %s\n", svg_path.c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_tandem_quality: %s\n", e.what());
    return 1;
  }
  return 0;
}
