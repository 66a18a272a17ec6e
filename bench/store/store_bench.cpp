// bench_store [DIR]: figures for the component store on this machine's disk. Writes its data under
// DIR (default: ./bench-store-data, removed at the end).
//   commits: LocalSink at batch sizes 1, 32, 256 (one fdatasync + one index transaction per batch),
//            and the same records without fdatasync, to show what durability costs;
//   reads:   checksum-verified reads of small and large components;
//   queries: 100 000 index rows, filters on volume, wrapped azimuth, box, counts;
//   exports: every format, one file, large components.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <random>

#include "geotandem/mesh/measure.hpp"
#include "geotandem/store/export.hpp"
#include "geotandem/store/local_sink.hpp"

using namespace geotandem;
using Clock = std::chrono::steady_clock;

namespace {

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

volume::Geometry geometry() {
  volume::Geometry g;
  g.shape = {1000, 1000, 500};
  g.affine = {600000.0, 25.0, 0.0, 6.7e6, 0.0, 25.0};
  return g;
}

mesh::SurfaceMesh sphere(int level, double radius, const mesh::Point& center) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  mesh::SurfaceMesh s;
  s.points = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
              {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  s.triangles = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                 {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                 {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int l = 0; l < level; ++l) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> middle;
    auto mid = [&](std::uint32_t a, std::uint32_t b) {
      auto [it, fresh] = middle.emplace(std::minmax(a, b), static_cast<std::uint32_t>(s.points.size()));
      if (fresh) {
        const auto &p = s.points[a], &q = s.points[b];
        s.points.push_back({(p[0] + q[0]) / 2, (p[1] + q[1]) / 2, (p[2] + q[2]) / 2});
      }
      return it->second;
    };
    std::vector<mesh::Triangle> next;
    for (auto [a, b, c] : s.triangles) {
      auto ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
      next.insert(next.end(), {{a, ab, ca}, {b, bc, ab}, {c, ca, bc}, {ab, bc, ca}});
    }
    s.triangles = std::move(next);
  }
  for (auto& p : s.points) {
    double n = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    for (int d = 0; d < 3; ++d)
      p[d] = center[d] + radius * p[d] / n;
  }
  return s;
}

mesh::Component component(std::uint64_t key, int level, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  mesh::Component c;
  c.key = key;
  c.surface = sphere(level, 2 + 6 * u(rng), {50 + 900 * u(rng), 50 + 900 * u(rng), 20 + 460 * u(rng)});
  c.stats.volume = 1e6 * u(rng);
  c.stats.azimuth = 180 * u(rng);
  c.stats.closed = true;
  return c;
}

std::uint64_t record_bytes(const mesh::Component& c) {
  return 48 + 24 * c.surface.points.size() + 12 * c.surface.triangles.size();
}

void bench_commits(const std::filesystem::path& root, const std::vector<mesh::Component>& components,
                   const char* what) {
  std::uint64_t bytes = 0;
  for (const auto& c : components)
    bytes += record_bytes(c);
  for (std::size_t batch : {1, 32, 256}) {
    auto dir = root / ("commit-" + std::string(what) + "-" + std::to_string(batch));
    auto store = store::ComponentStore::create(dir, geometry());
    auto start = Clock::now();
    {
      store::LocalSink sink(store, {"local", std::nullopt, batch});
      for (const auto& c : components)
        sink.commit(c);
      sink.close();
    }
    double s = seconds_since(start);
    std::printf("commit  %-6s batch %4zu  %6zu components %8.1f MB  %7.3f s  %9.0f components/s  %7.1f MB/s\n", what,
                batch, components.size(), bytes / 1e6, s, components.size() / s, bytes / 1e6 / s);
  }
  // The same appends and index rows with fdatasync off: the cost of durability.
  auto dir = root / ("commit-" + std::string(what) + "-nosync");
  auto store = store::ComponentStore::create(dir, geometry());
  auto start = Clock::now();
  store::ShardWriterOptions options;
  options.durable = false;
  store::ShardWriter writer(dir, "w", geometry(), options);
  std::vector<store::IndexEntry> entries;
  for (const auto& c : components) {
    entries.push_back({c.key, writer.append(c), c.stats, std::nullopt});
    if (entries.size() == 256) {
      store.commit(entries);
      entries.clear();
    }
  }
  store.commit(entries);
  double s = seconds_since(start);
  std::printf("commit  %-6s no fdatasync, index batch 256 %6zu components  %7.3f s  %9.0f components/s  %7.1f MB/s\n",
              what, components.size(), s, components.size() / s, bytes / 1e6 / s);
}

void bench_reads(const std::filesystem::path& dir, const char* what) {
  auto store = store::ComponentStore::open(dir);
  auto rows = store.query();
  std::uint64_t bytes = 0;
  auto start = Clock::now();
  for (const auto& row : rows) {
    auto surface = store.read(row);
    bytes += row.location.length;
  }
  double s = seconds_since(start);
  std::printf("read    %-6s %6zu components %8.1f MB  %7.3f s  %9.0f components/s  %7.1f MB/s (page cache warm)\n",
              what, rows.size(), bytes / 1e6, s, rows.size() / s, bytes / 1e6 / s);
}

void bench_queries(const std::filesystem::path& root) {
  auto dir = root / "queries";
  auto store = store::ComponentStore::create(dir, geometry());
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const std::size_t rows = 100000;
  // Index rows only: queries never read shards, so the records they point at need not exist.
  std::vector<store::IndexEntry> entries;
  auto start = Clock::now();
  for (std::uint64_t key = 1; key <= rows; ++key) {
    store::IndexEntry e;
    e.key = key * 7;
    e.location = {"w", key * 1000, 48 + 24 * 42 + 12 * 80, key, 42, 80};
    e.stats.volume = std::exp(20 * u(rng));
    e.stats.azimuth = 180 * u(rng);
    double x = 600000 + 25000 * u(rng), y = 6.7e6 + 25000 * u(rng), z = 2000 * u(rng);
    e.stats.box_min = {x, y, z};
    e.stats.box_max = {x + 200 * u(rng), y + 200 * u(rng), z + 40 * u(rng)};
    e.stats.closed = u(rng) < 0.9;
    entries.push_back(e);
    if (entries.size() == 5000) {
      store.commit(entries);
      entries.clear();
    }
  }
  std::printf("index   %zu rows committed in %.2f s (batches of 5000)\n", rows, seconds_since(start));
  struct Case {
    const char* name;
    store::Query query;
  };
  std::vector<Case> cases(6);
  cases[0].name = "all rows, by key";
  cases[1].name = "volume >= 1e8 (indexed)";
  cases[1].query.min_volume = 1e8;
  cases[2].name = "azimuth 170:10 (wraps)";
  cases[2].query.azimuth = store::parse_azimuth_range("170:10");
  cases[3].name = "box 5 km x 5 km";
  cases[3].query.box = store::parse_world_box("605000,6705000,0,610000,6710000,2000");
  cases[4].name = "closed, volume >= 1e6, top 100 by volume";
  cases[4].query.closed_only = true;
  cases[4].query.min_volume = 1e6;
  cases[4].query.sort = store::SortKey::volume;
  cases[4].query.descending = true;
  cases[4].query.limit = 100;
  cases[5].name = "azimuth 30:60 and volume in [1e4, 1e7]";
  cases[5].query.azimuth = store::parse_azimuth_range("30:60");
  cases[5].query.min_volume = 1e4;
  cases[5].query.max_volume = 1e7;
  for (const auto& c : cases) {
    auto t0 = Clock::now();
    auto result = store.query(c.query);
    double s = seconds_since(t0);
    t0 = Clock::now();
    auto n = store.count(c.query);
    double sc = seconds_since(t0);
    std::printf("query   %-42s %7zu rows  %8.2f ms   count %7llu in %6.2f ms\n", c.name, result.size(), s * 1e3,
                static_cast<unsigned long long>(n), sc * 1e3);
  }
}

void bench_exports(const std::filesystem::path& store_dir, const std::filesystem::path& root) {
  auto store = store::ComponentStore::open(store_dir);
  auto rows = store.query();
  for (auto format :
       {store::ExportFormat::ply, store::ExportFormat::obj, store::ExportFormat::vtp, store::ExportFormat::tsurf}) {
    auto out = root / (std::string("export.") + store::file_extension(format));
    NullProgress progress;
    auto start = Clock::now();
    auto summary = store::export_components(store, rows, out, {format}, progress, CancelToken{});
    double s = seconds_since(start);
    double mb = std::filesystem::file_size(out) / 1e6;
    std::printf("export  %-4s %3llu components %8llu triangles  %7.3f s  %7.1f MB written  %6.1f MB/s  %5.2f M "
                "triangles/s\n",
                store::file_extension(format), static_cast<unsigned long long>(summary.components),
                static_cast<unsigned long long>(summary.triangles), s, mb, mb / s, summary.triangles / 1e6 / s);
  }
}

} // namespace

int main(int argc, char** argv) {
  std::filesystem::path root = argc > 1 ? argv[1] : "bench-store-data";
  std::filesystem::remove_all(root);
  std::filesystem::create_directories(root);
  std::mt19937_64 rng(1);
  std::vector<mesh::Component> small, large;
  for (std::uint64_t key = 1; key <= 1000; ++key)
    small.push_back(component(key, 1, rng));
  for (std::uint64_t key = 1; key <= 24; ++key)
    large.push_back(component(key, 6, rng));
  std::printf("small: 1000 components of %zu triangles; large: 24 components of %zu triangles\n",
              small[0].surface.triangles.size(), large[0].surface.triangles.size());
  bench_commits(root, small, "small");
  bench_commits(root, large, "large");
  bench_reads(root / "commit-small-32", "small");
  bench_reads(root / "commit-large-32", "large");
  bench_queries(root);
  bench_exports(root / "commit-large-32", root);
  std::filesystem::remove_all(root);
  return 0;
}
