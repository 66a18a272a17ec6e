// store_writer DIR COUNT [FIRST_KEY]: a store of COUNT small closed bodies (octahedra of varying
// size and place in a 200^3 cube) with keys FIRST_KEY, FIRST_KEY + 7, ..., written through the C++
// store API (ShardWriter + ComponentStore::commit), with a selection "every_other". The Python
// tests use it for keys at and above 2^63 (which extraction of a real cube never reaches), the
// benchmark for a store of 200,000 components.

#include <charconv>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "geotandem/core/error.hpp"
#include "geotandem/mesh/measure.hpp"
#include "geotandem/store/shard.hpp"
#include "geotandem/store/store.hpp"

using namespace geotandem;

namespace {

std::uint64_t number(const char* text) {
  std::uint64_t value = 0;
  auto [end, ec] = std::from_chars(text, text + std::strlen(text), value);
  if (ec != std::errc() || *end != '\0') throw InvalidArgument(std::string("not a number: ") + text);
  return value;
}

// An octahedron around (ci, cj, ck) with half-diagonals r, r, r/2, in index coordinates.
mesh::SurfaceMesh octahedron(double ci, double cj, double ck, double r) {
  mesh::SurfaceMesh s;
  s.points = {{ci + r, cj, ck}, {ci - r, cj, ck},     {ci, cj + r, ck},
              {ci, cj - r, ck}, {ci, cj, ck + r / 2}, {ci, cj, ck - r / 2}};
  s.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  return s;
}

} // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: store_writer DIR COUNT [FIRST_KEY]\n");
    return 2;
  }
  try {
    const std::uint64_t count = number(argv[2]);
    const std::uint64_t first = argc > 3 ? number(argv[3]) : 1;
    volume::Geometry g;
    g.shape = {200, 200, 200};
    auto store = store::ComponentStore::create(argv[1], g, {"store_writer test store", "store_writer"});
    const std::int64_t run = store.begin_run(R"({"command": "store_writer"})");
    store::ShardWriter writer(argv[1], "writer", g);
    std::vector<store::IndexEntry> batch;
    std::vector<std::uint64_t> every_other;
    for (std::uint64_t n = 0; n < count; ++n) {
      const double r = 1.0 + static_cast<double>(n % 5);
      const auto surface = octahedron(10 + static_cast<double>(n * 37 % 180), 10 + static_cast<double>(n * 53 % 180),
                                      10 + static_cast<double>(n * 11 % 180), r);
      mesh::Component c;
      c.key = first + n * 7;
      c.surface = surface;
      c.stats = mesh::measure_component(surface, g);
      store::IndexEntry e;
      e.key = c.key;
      e.location = writer.append(c);
      e.stats = c.stats;
      e.run = run;
      batch.push_back(e);
      if (n % 2 == 0) every_other.push_back(c.key);
      if (batch.size() == 10000 || n + 1 == count) {
        writer.sync();
        store.commit(batch);
        batch.clear();
      }
    }
    store.save_selection("every_other", every_other, R"({"made_by": "store_writer"})");
    store.end_run(run, R"({"components": )" + std::to_string(count) + "}");
    return 0;
  } catch (const Error& e) {
    std::fprintf(stderr, "store_writer: %s\n", e.what());
    return e.exit_code();
  }
}
