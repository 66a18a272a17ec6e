// bench_flying_edges_meshopt (issue 57, part 3): side by side on one core, `geotandem extract
// --workers 0` against the fastest general-purpose route, VTK's vtkFlyingEdges3D followed by
// meshoptimizer's meshopt_simplify to the same triangle count.
//   bench_flying_edges_meshopt GEOTANDEM [edge=512] [dir=/tmp/geotandem-fe-meshopt] [seed=1] [iso=0.5]
//                              [spacing=0.5]
// The cube is the bench's own (flying_edges/noisy_cube.hpp), written once as a geotandem raw cube
// in `dir` and reused while its file is there. geotandem runs as a child process (wall time, and
// user + system CPU from wait4); its surface is read back from `store export --format ply
// --no-caps`. VTK runs in this process with its SMP backend set to Sequential. Both outputs are
// measured against two full-resolution surfaces: FlyingEdges3D's, and geotandem's own marching
// cubes (`extract --max-error 1e-6`, the smallest E0 it takes, at which nothing moves by more
// than 1e-6 voxel), the surface its E0 guarantee is stated against. Distances are in voxels,
// sampled every `spacing` voxels on both surfaces. Prints figures only: not a test.
#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <meshoptimizer.h>
#include <vtkCellArray.h>
#include <vtkFloatArray.h>
#include <vtkFlyingEdges3D.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include "bench_args.hpp"
#include "flying_edges/child_and_ply.hpp"
#include "flying_edges/noisy_cube.hpp"
#include "flying_edges/surface_distance.hpp"

namespace geotandem::bench {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// Bump when the generator changes, so that a cube left in `dir` by another build is not reused.
constexpr int kGeneratorVersion = 2;

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

double process_cpu() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// geotandem extract: times, its summary line, its surface (the store exported without caps).
struct GeotandemRun {
  Timing time;
  std::string summary;
  long long marching_cubes_triangles = -1;
  double extraction_seconds = -1.0; // what geotandem reports for the extraction itself
  Surface surface;
};

GeotandemRun run_geotandem(const std::string& exe, const fs::path& cube, double iso, double max_error,
                           const fs::path& dir, const std::string& name) {
  GeotandemRun r;
  const fs::path store = dir / ("store-" + name);
  char iso_text[64], e0_text[64];
  std::snprintf(iso_text, sizeof iso_text, "%.17g", iso);
  std::snprintf(e0_text, sizeof e0_text, "%.17g", max_error);
  r.time = run_child({exe, "extract", cube.string(), "--iso", iso_text, "--max-error", e0_text, "--workers", "0",
                      "--out", store.string(), "--fresh"},
                     dir / (name + ".stdout"), dir / (name + ".stderr"));
  const std::string out = read_text(dir / (name + ".stdout"));
  r.summary = out.substr(0, out.find('\n'));
  std::smatch m;
  if (std::regex_search(r.summary, m, std::regex(R"(from (\d+) marching-cubes triangles in ([0-9.]+) s)"))) {
    r.marching_cubes_triangles = std::stoll(m[1]);
    r.extraction_seconds = std::stod(m[2]);
  }
  const fs::path ply = dir / (name + ".ply");
  run_child(
      {exe, "store", "export", store.string(), "--format", "ply", "--no-caps", "--overwrite", "--out", ply.string()},
      dir / (name + "-export.stdout"), dir / (name + "-export.stderr"));
  r.surface = read_ply(ply);
  return r;
}

// FlyingEdges3D's points are (x, y, z) = (k, j, i) of the [i][j][k] array; geotandem's are
// (i, j, k). The distances compare them in geotandem's order.
Surface to_ijk(const float* xyz, std::size_t vertices, std::vector<std::uint32_t> corners) {
  Surface s;
  s.xyz.resize(3 * vertices);
  for (std::size_t v = 0; v < vertices; ++v) {
    s.xyz[3 * v] = xyz[3 * v + 2];
    s.xyz[3 * v + 1] = xyz[3 * v + 1];
    s.xyz[3 * v + 2] = xyz[3 * v];
  }
  s.corners = std::move(corners);
  return s;
}

// A simplified surface against a full-resolution one, both ways.
struct Pair {
  Sampled there, back; // simplified -> reference, reference -> simplified
  // Over the samples more than `margin` from the cube's faces, or over all of them.
  double max(bool all) const {
    return all ? std::max(there.all.max, back.all.max) : std::max(there.inside.max, back.inside.max);
  }
  double mean(bool all) const {
    const Distance& a = all ? there.all : there.inside;
    const Distance& b = all ? back.all : back.inside;
    const double area = a.area + b.area;
    return area > 0 ? (a.weighted_sum + b.weighted_sum) / area : 0.0;
  }
};

Pair compare(const Surface& simplified, const TriangleGrid& simplified_grid, const Surface& reference,
             const TriangleGrid& reference_grid, double spacing, const Box& inside, double beyond) {
  return {sampled_distance(simplified, reference_grid, spacing, inside, beyond),
          sampled_distance(reference, simplified_grid, spacing, inside, beyond)};
}

// Threads of this process now (/proc/self/status), to show that VTK ran on one.
int thread_count() {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("Threads:", 0) == 0) return std::stoi(line.substr(8));
  return -1;
}

int bench_main(int argc, char** argv) {
  // One thread for VTK: its SMP tools read these when first used (vtkSMPTools.h documents both;
  // the header itself cannot be included here, VTK 9.1's is not valid C++20). The thread count
  // printed after FlyingEdges3D checks it: TBB or std::thread backends would start workers.
  setenv("VTK_SMP_BACKEND_IN_USE", "Sequential", 1);
  setenv("VTK_SMP_MAX_THREADS", "1", 1);
  const Args args(argc, argv,
                  "bench_flying_edges_meshopt GEOTANDEM [edge=512] [dir=/tmp/geotandem-fe-meshopt] [seed=1] "
                  "[iso=0.5] [spacing=0.5]");
  if (args.size() < 1) args.fail(1, "is missing: the geotandem executable to time");
  const std::string exe = fs::absolute(args.text(1, "")).string();
  const std::int64_t edge = args.integer(2, 512, 8);
  const fs::path dir = args.text(3, "/tmp/geotandem-fe-meshopt");
  const auto seed = static_cast<std::uint64_t>(args.integer(4, 1, 0));
  const double iso = args.real(5, 0.5, -1e30);
  const double spacing = args.real(6, 0.5, 0.01);
  const double max_error = 0.5; // geotandem's default E0
  fs::create_directories(dir);

  // 1. The cube, made once per edge, seed and generator version.
  const fs::path cube = dir / ("noisy-" + std::to_string(edge) + "-seed" + std::to_string(seed) + "-v" +
                               std::to_string(kGeneratorVersion) + ".raw");
  if (fs::exists(cube.string() + ".json") && fs::exists(cube) &&
      fs::file_size(cube) == static_cast<std::uintmax_t>(edge * edge * edge) * sizeof(float)) {
    std::printf("cube: %s (reused)\n", cube.c_str());
  } else {
    const auto t = Clock::now();
    NoisyCubeOptions o;
    o.edge = edge;
    o.seed = seed;
    write_raw_cube(make_noisy_cube(o), edge, cube);
    std::printf("cube: %s (generated and written in %.1f s)\n", cube.c_str(), seconds_since(t));
  }
  std::printf("%lld^3 float32 samples, iso %g, geotandem E0 %g voxel (its default), alpha and leaves at their "
              "defaults\n",
              static_cast<long long>(edge), iso, max_error);
  std::fflush(stdout);

  // 2. geotandem, timed; then its full-resolution marching cubes (not timed for the comparison).
  const GeotandemRun gt = run_geotandem(exe, cube, iso, max_error, dir, "geotandem");
  const GeotandemRun full = run_geotandem(exe, cube, iso, 1e-6, dir, "geotandem-full");

  // 3. FlyingEdges3D + meshopt_simplify in this process, on one thread.
  const auto read_start = Clock::now();
  const double read_cpu0 = process_cpu();
  const std::unique_ptr<float[]> samples = read_raw_cube(cube, edge);
  const Timing read_time{seconds_since(read_start), process_cpu() - read_cpu0};

  vtkNew<vtkFloatArray> scalars;
  scalars->SetNumberOfComponents(1);
  scalars->SetArray(samples.get(), static_cast<vtkIdType>(edge * edge * edge), 1); // 1: VTK does not own or free it
  vtkNew<vtkImageData> image;
  image->SetDimensions(static_cast<int>(edge), static_cast<int>(edge), static_cast<int>(edge)); // x = k fastest
  image->SetSpacing(1.0, 1.0, 1.0);
  image->SetOrigin(0.0, 0.0, 0.0);
  image->GetPointData()->SetScalars(scalars);
  vtkNew<vtkFlyingEdges3D> flying;
  flying->SetInputData(image);
  flying->SetValue(0, iso);
  flying->ComputeNormalsOff();
  flying->ComputeGradientsOff();
  flying->ComputeScalarsOff();
  flying->InterpolateAttributesOff();
  auto start = Clock::now();
  double cpu0 = process_cpu();
  flying->Update();
  const Timing fe_time{seconds_since(start), process_cpu() - cpu0};
  vtkPolyData* fe = flying->GetOutput();

  // The index buffer meshoptimizer takes, from VTK's cell array (counted with meshopt's time).
  start = Clock::now();
  cpu0 = process_cpu();
  vtkCellArray* polys = fe->GetPolys();
  const auto fe_triangles = static_cast<std::size_t>(polys->GetNumberOfCells());
  std::vector<std::uint32_t> indices(3 * fe_triangles);
  vtkDataArray* connectivity = polys->GetConnectivityArray();
  if (static_cast<std::size_t>(connectivity->GetNumberOfValues()) != indices.size())
    throw std::runtime_error("FlyingEdges3D gave cells that are not all triangles");
  if (polys->IsStorage64Bit()) {
    const auto* c = polys->GetConnectivityArray64()->GetPointer(0);
    for (std::size_t n = 0; n < indices.size(); ++n)
      indices[n] = static_cast<std::uint32_t>(c[n]);
  } else {
    const auto* c = polys->GetConnectivityArray32()->GetPointer(0);
    for (std::size_t n = 0; n < indices.size(); ++n)
      indices[n] = static_cast<std::uint32_t>(c[n]);
  }
  auto* fe_points = vtkFloatArray::SafeDownCast(fe->GetPoints()->GetData());
  if (fe_points == nullptr) throw std::runtime_error("FlyingEdges3D's points are not float32");
  const float* positions = fe_points->GetPointer(0);
  const auto fe_vertices = static_cast<std::size_t>(fe->GetNumberOfPoints());
  // Weld: FlyingEdges3D shares the points of an edge between its cells, so the remap finds
  // nothing to merge; it is timed anyway, since a route that does not know that needs it.
  std::vector<unsigned int> remap(fe_vertices);
  const std::size_t unique = meshopt_generateVertexRemap(remap.data(), indices.data(), indices.size(), positions,
                                                         fe_vertices, 3 * sizeof(float));
  std::vector<float> welded;
  if (unique < fe_vertices) {
    meshopt_remapIndexBuffer(indices.data(), indices.data(), indices.size(), remap.data());
    welded.resize(3 * unique);
    meshopt_remapVertexBuffer(welded.data(), positions, fe_vertices, 3 * sizeof(float), remap.data());
    positions = welded.data();
  }
  const std::size_t vertices = unique < fe_vertices ? unique : fe_vertices;
  const Timing weld_time{seconds_since(start), process_cpu() - cpu0};

  const std::size_t target = 3 * gt.surface.triangles();
  std::vector<std::uint32_t> simplified(indices.size());
  float relative_error = 0.0f;
  start = Clock::now();
  cpu0 = process_cpu();
  // target_error 1: any error (relative to the mesh's extent), so that only the count stops it.
  simplified.resize(meshopt_simplify(simplified.data(), indices.data(), indices.size(), positions, vertices,
                                     3 * sizeof(float), target, 1.0f, 0, &relative_error));
  const Timing mo_time{seconds_since(start), process_cpu() - cpu0};
  // The same with meshopt_SimplifyLockBorder: the rims on the cube's faces stay where they are.
  std::vector<std::uint32_t> locked(indices.size());
  start = Clock::now();
  cpu0 = process_cpu();
  locked.resize(meshopt_simplify(locked.data(), indices.data(), indices.size(), positions, vertices, 3 * sizeof(float),
                                 target, 1.0f, meshopt_SimplifyLockBorder, nullptr));
  const Timing locked_time{seconds_since(start), process_cpu() - cpu0};
  const int threads = thread_count();
  const double meshopt_error = relative_error * meshopt_simplifyScale(positions, vertices, 3 * sizeof(float));

  // 4. Quality: distances to both full-resolution surfaces, shape, edges. The open surfaces end on
  // the cube's faces, where geotandem's caps close them; caps are simplified like the rest, so a rim
  // may slide along its face (the E0 guarantee holds for the capped surface), and meshopt moves
  // border vertices too unless locked. Hence figures without the samples within `margin` of a face.
  const Surface fe_surface = to_ijk(positions, vertices, indices);
  const Surface mo_surface = to_ijk(positions, vertices, simplified);
  const Surface locked_surface = to_ijk(positions, vertices, locked);
  const double margin = 1.0;
  Box inside;
  for (int a = 0; a < 3; ++a) {
    inside.lo[a] = margin;
    inside.hi[a] = static_cast<double>(edge - 1) - margin;
  }
  const double cell = 2.0;
  const auto dist_start = Clock::now();
  const TriangleGrid fe_grid(fe_surface, cell), full_grid(full.surface, cell), gt_grid(gt.surface, cell),
      mo_grid(mo_surface, cell), locked_grid(locked_surface, cell);
  const Pair gt_fe = compare(gt.surface, gt_grid, fe_surface, fe_grid, spacing, inside, max_error);
  const Pair gt_full = compare(gt.surface, gt_grid, full.surface, full_grid, spacing, inside, max_error);
  const Pair mo_fe = compare(mo_surface, mo_grid, fe_surface, fe_grid, spacing, inside, max_error);
  const Pair mo_full = compare(mo_surface, mo_grid, full.surface, full_grid, spacing, inside, max_error);
  const Pair locked_fe = compare(locked_surface, locked_grid, fe_surface, fe_grid, spacing, inside, max_error);
  const Pair locked_full = compare(locked_surface, locked_grid, full.surface, full_grid, spacing, inside, max_error);
  const Pair fe_full = compare(fe_surface, fe_grid, full.surface, full_grid, spacing, inside, max_error);
  const double dist_seconds = seconds_since(dist_start);

  // 5. The table.
  std::printf("\nVTK: VTK_SMP_BACKEND_IN_USE=Sequential, %d thread(s) in this process after FlyingEdges3D and "
              "meshopt\ngeotandem: %s\n",
              threads, gt.summary.c_str());
  std::printf("full resolution: FlyingEdges3D %zu triangles; geotandem's marching cubes %lld triangles, %zu after "
              "extract --max-error 1e-6 (\"geotandem MC\" below)\n",
              fe_triangles, full.marching_cubes_triangles, full.surface.triangles());
  std::printf("Hausdorff distances in voxels, both directions, sampled every %g voxel: max and area-weighted mean "
              "over the samples more than %g voxel from the cube's faces, and max over all samples (rims on the "
              "faces included)\n\n",
              spacing, margin);
  std::printf("%-34s %7s %7s %9s | %-24s | %-24s | %5s\n", "", "wall s", "CPU s", "triangles", "to FlyingEdges3D",
              "to geotandem MC", "aniso");
  std::printf("%-34s %7s %7s %9s | %6s %7s %9s | %6s %7s %9s | %5s\n", "", "", "", "", "max", "mean", "max all", "max",
              "mean", "max all", "");
  auto row = [](const char* name, const Timing& t, std::size_t triangles, const Pair* to_fe, const Pair* to_full,
                const Surface* surface) {
    std::printf("%-34s %7.3f %7.3f %9zu |", name, t.wall, t.cpu, triangles);
    for (const Pair* p : {to_fe, to_full})
      if (p)
        std::printf(" %6.3f %7.4f %9.3f |", p->max(false), p->mean(false), p->max(true));
      else
        std::printf(" %6s %7s %9s |", "-", "-", "-");
    if (surface)
      std::printf(" %5.3f\n", anisotropy(*surface));
    else
      std::printf(" %5s\n", "-");
  };
  const Timing route{fe_time.wall + weld_time.wall + mo_time.wall, fe_time.cpu + weld_time.cpu + mo_time.cpu};
  row("geotandem extract --workers 0", gt.time, gt.surface.triangles(), &gt_fe, &gt_full, &gt.surface);
  row("FlyingEdges3D (full resolution)", fe_time, fe_triangles, nullptr, &fe_full, &fe_surface);
  row("index buffer + weld check", weld_time, fe_triangles, nullptr, nullptr, nullptr);
  row("meshopt_simplify", mo_time, mo_surface.triangles(), &mo_fe, &mo_full, &mo_surface);
  row("FlyingEdges3D + meshopt", route, mo_surface.triangles(), &mo_fe, &mo_full, &mo_surface);
  std::printf("%-34s %7.3f %7.3f\n", "ratio geotandem / (FE + meshopt)", gt.time.wall / route.wall,
              gt.time.cpu / route.cpu);
  std::printf("%-34s %7.3f %7.3f   (raw file from the page cache; geotandem reads it itself)\n",
              "read the cube into memory", read_time.wall, read_time.cpu);
  std::printf("%-34s %7.3f %7.3f\n", "ratio geotandem / (read+FE+meshopt)",
              gt.time.wall / (read_time.wall + route.wall), gt.time.cpu / (read_time.cpu + route.cpu));
  row("meshopt_simplify, border locked", locked_time, locked_surface.triangles(), &locked_fe, &locked_full,
      &locked_surface);

  auto at = [](const Distance& d) {
    char text[96];
    std::snprintf(text, sizeof text, "%.3f at (%.2f, %.2f, %.2f)", d.max, d.where[0], d.where[1], d.where[2]);
    return std::string(text);
  };
  std::printf("\none-sided maxima, simplified -> full / full -> simplified, at (i, j, k) in voxels; all samples, "
              "then those more than %g voxel from the faces (a maximum far above E0 on meshopt's side is a small "
              "body it removed):\n",
              margin);
  auto one_sided = [&](const char* name, const Pair& p) {
    std::printf("  %-26s %s / %s\n  %-26s %s / %s\n", name, at(p.there.all).c_str(), at(p.back.all).c_str(), "",
                at(p.there.inside).c_str(), at(p.back.inside).c_str());
    std::printf("  %-26s area farther than E0 (%g): %.4f %% / %.4f %% of the samples' area\n", "", max_error,
                100.0 * p.there.inside.area_beyond / std::max(p.there.inside.area, 1e-300),
                100.0 * p.back.inside.area_beyond / std::max(p.back.inside.area, 1e-300));
  };
  one_sided("geotandem to geotandem MC", gt_full);
  one_sided("geotandem to FE", gt_fe);
  one_sided("meshopt to FE", mo_fe);
  one_sided("meshopt (locked) to FE", locked_fe);
  one_sided("FE to geotandem MC", fe_full);
  std::printf("geotandem: %.3f s of extraction by its own count (the rest of its wall time: start, value scan, "
              "store); the full-resolution run took %.3f s\n",
              gt.extraction_seconds, full.time.wall);
  std::printf("FlyingEdges3D: %zu points, %zu unique after the weld check; meshopt_simplify: target %zu triangles, "
              "reached %zu (border locked: %zu), its own error estimate %.3f voxel\n",
              fe_vertices, unique, target / 3, mo_surface.triangles(), locked_surface.triangles(), meshopt_error);
  auto edges = [](const char* name, const Surface& surface) {
    const EdgeCounts e = count_edges(surface);
    std::printf("  %-32s %zu non-manifold edges, %zu border edges, %zu triangles with two equal corners\n", name,
                e.non_manifold, e.border, e.degenerate_triangles);
  };
  std::printf("edges:\n");
  edges("geotandem", gt.surface);
  edges("FlyingEdges3D", fe_surface);
  edges("meshopt_simplify", mo_surface);
  edges("meshopt_simplify, border locked", locked_surface);
  std::printf("distances took %.1f s; samples: %zu + %zu (geotandem, FE), %zu + %zu (meshopt, FE)\n", dist_seconds,
              gt_fe.there.all.samples, gt_fe.back.all.samples, mo_fe.there.all.samples, mo_fe.back.all.samples);
  return 0;
}

} // namespace
} // namespace geotandem::bench

int main(int argc, char** argv) {
  return geotandem::bench::guarded_main("bench_flying_edges_meshopt",
                                        [&] { return geotandem::bench::bench_main(argc, argv); });
}
