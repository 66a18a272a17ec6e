// bench_store_check [COUNT] [DIR]: `store check` on a store of COUNT components (default 100 000):
// builds the store (records written without fdatasync, index rows in batches of 1000), then times
// check_store, which reads back and verifies every record. Prints the figures; data under DIR
// (default ./bench-store-check-data, removed at the end).

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "geotandem/store/check.hpp"
#include "geotandem/store/store.hpp"

using namespace geotandem;
using Clock = std::chrono::steady_clock;

namespace {

// An octahedron around (x, y, z): 6 vertices, 8 triangles, a closed surface.
mesh::SurfaceMesh octahedron(double x, double y, double z, double r) {
  mesh::SurfaceMesh s;
  s.points = {{x + r, y, z}, {x - r, y, z}, {x, y + r, z}, {x, y - r, z}, {x, y, z + r}, {x, y, z - r}};
  s.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  return s;
}

} // namespace

int main(int argc, char** argv) {
  const std::uint64_t count = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 100000;
  const std::filesystem::path root = argc > 2 ? argv[2] : "bench-store-check-data";
  std::filesystem::remove_all(root);
  volume::Geometry g;
  g.shape = {1000, 1000, 500};
  g.affine = {600000.0, 25.0, 0.0, 6.7e6, 0.0, 25.0};

  auto start = Clock::now();
  {
    auto store = store::ComponentStore::create(root / "store", g);
    store::ShardWriterOptions options;
    options.durable = false;
    store::ShardWriter writer(root / "store", "w", g, options);
    std::vector<store::IndexEntry> batch;
    for (std::uint64_t key = 1; key <= count; ++key) {
      const double x = 600000.0 + static_cast<double>(key % 1000) * 25.0, y = 6.7e6 + static_cast<double>(key / 1000);
      store::IndexEntry e;
      e.key = key;
      e.location = writer.append_world(key, octahedron(x, y, 100.0, 10.0));
      e.stats.volume = 1333.3;
      e.stats.closed = true;
      batch.push_back(e);
      if (batch.size() == 1000 || key == count) {
        writer.sync();
        store.commit(batch);
        batch.clear();
      }
    }
  }
  const double build_s = std::chrono::duration<double>(Clock::now() - start).count();

  auto store = store::ComponentStore::open(root / "store");
  NullProgress quiet;
  start = Clock::now();
  auto report = store::check_store(store, quiet, CancelToken{});
  const double check_s = std::chrono::duration<double>(Clock::now() - start).count();
  const auto shard_bytes = std::filesystem::file_size(root / "store/shards/w.gts");
  std::printf("store check: %llu components (%.1f MiB of records) built in %.2f s\n",
              static_cast<unsigned long long>(report.checked), static_cast<double>(shard_bytes) / (1 << 20), build_s);
  std::printf("store check: verified in %.3f s (%.0f components/s, %.1f MiB/s); %zu damaged\n", check_s,
              static_cast<double>(report.checked) / check_s, static_cast<double>(shard_bytes) / (1 << 20) / check_s,
              report.damaged.size());
  std::filesystem::remove_all(root);
  return report.damaged.empty() && report.checked == count ? 0 : 1;
}
