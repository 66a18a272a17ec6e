// Caps in the store: cut_faces and cap_area round trip, exports with and without caps, and stores
// written before caps (no cut_faces / cap_area columns) still open, read-only and for writing.

#include <gtest/gtest.h>

#include <sqlite3.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "fixtures.hpp"
#include "geotandem/mesh/caps.hpp"
#include "geotandem/mesh/measure.hpp"
#include "geotandem/mesh/topology.hpp"
#include "geotandem/store/export.hpp"
#include "geotandem/store/local_sink.hpp"
#include "geotandem/store/store.hpp"
#include "scratch.hpp"

namespace geotandem::store {
namespace {

using geotandem::testing::ScratchDir;

// A box of cells [lo, hi] in index coordinates, closed, counter-clockwise seen from outside.
mesh::SurfaceMesh box(const std::array<double, 3>& lo, const std::array<double, 3>& hi) {
  mesh::SurfaceMesh s;
  for (int c = 0; c < 8; ++c)
    s.points.push_back({(c & 1) ? hi[0] : lo[0], (c & 2) ? hi[1] : lo[1], (c & 4) ? hi[2] : lo[2]});
  // Each face as a quad, counter-clockwise seen from outside.
  const int quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  for (const auto& q : quads) {
    s.triangles.push_back(
        {static_cast<std::uint32_t>(q[0]), static_cast<std::uint32_t>(q[1]), static_cast<std::uint32_t>(q[2])});
    s.triangles.push_back(
        {static_cast<std::uint32_t>(q[0]), static_cast<std::uint32_t>(q[2]), static_cast<std::uint32_t>(q[3])});
  }
  return s;
}

mesh::Component component(std::uint64_t key, const mesh::SurfaceMesh& s, const volume::Geometry& g) {
  mesh::Component c;
  c.key = key;
  c.surface = s;
  c.stats = mesh::measure_component(s, g);
  return c;
}

// Two bodies: one cut by the faces i- and k+ (a box against them), one inside.
std::filesystem::path make_store(const ScratchDir& scratch) {
  const auto g = testing::test_geometry(); // 60 x 50 x 40
  auto dir = scratch.path() / "store";
  auto store = ComponentStore::create(dir, g, {"caps", "caps_test"});
  LocalSink sink(store, {"local", std::nullopt, 4});
  sink.commit(component(7, box({0, 10, 30}, {5, 16, 39}), g));
  sink.commit(component(9, box({20, 20, 10}, {24, 25, 14}), g));
  sink.close();
  return dir;
}

TEST(StoreCaps, CutFacesAndCapAreaRoundTrip) {
  ScratchDir scratch;
  const auto store = ComponentStore::open(make_store(scratch));
  const auto cut = store.find(7);
  ASSERT_TRUE(cut);
  EXPECT_TRUE(cut->stats.closed);
  EXPECT_TRUE(cut->stats.cut_by_border);
  EXPECT_EQ(mesh::cut_faces_text(cut->stats.cut_faces), "i-,k+");
  // The i- cap is 6 x 9 cells, the k+ cap 5 x 6; a cell's world area on those planes follows the
  // survey (25 m bins) and the 4 ms samples.
  const double bin = 25.0, ms = 4.0;
  EXPECT_NEAR(cut->stats.cap_area, 6 * 9 * bin * ms + 5 * 6 * bin * bin, 1e-6 * cut->stats.area);
  EXPECT_GT(cut->stats.volume, 0.0);
  const auto inside = store.find(9);
  ASSERT_TRUE(inside);
  EXPECT_FALSE(inside->stats.cut_by_border);
  EXPECT_EQ(inside->stats.cut_faces, 0);
  EXPECT_EQ(inside->stats.cap_area, 0.0);
  Query q;
  q.closed_only = true;
  ASSERT_EQ(store.query(q).size(), 1u); // closed by itself: the caps do not count
  EXPECT_EQ(store.query(q)[0].key, 9u);
}

TEST(StoreCaps, ExportsKeepCapsUnlessAskedNotTo) {
  ScratchDir scratch;
  const auto store = ComponentStore::open(make_store(scratch));
  const auto rows = store.query();
  NullProgress progress;
  for (bool caps : {true, false}) {
    ExportOptions options;
    options.format = ExportFormat::obj;
    options.caps = caps;
    const auto out = scratch.path() / (caps ? "with.obj" : "without.obj");
    export_components(store, rows, out, options, progress, CancelToken{});
    std::ifstream in(out);
    std::size_t faces = 0;
    for (std::string line; std::getline(in, line);)
      faces += line.rfind("f ", 0) == 0 ? 1 : 0;
    EXPECT_EQ(faces, caps ? 24u : 20u) << caps;
    options.format = ExportFormat::ply;
    const auto ply = scratch.path() / (caps ? "with.ply" : "without.ply");
    const auto summary = export_components(store, rows, ply, options, progress, CancelToken{});
    std::ifstream header(ply, std::ios::binary);
    std::string text, line;
    while (std::getline(header, line) && line != "end_header")
      text += line + "\n";
    EXPECT_NE(text.find(caps ? "element face 24" : "element face 20"), std::string::npos) << text;
    EXPECT_EQ(summary.components, 2u);
  }
  // Without caps the cut body is the open surface: its border lies on the cut faces.
  const auto world = store.read(7);
  const auto open = mesh::without_world_caps(world, store.geometry());
  EXPECT_EQ(open.triangles.size(), 8u);
  EXPECT_EQ(mesh::check_topology(open).boundary_edges, 6u); // around the two removed faces
}

void drop_cap_columns(const std::filesystem::path& dir) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open((dir / "index.sqlite").c_str(), &db), SQLITE_OK);
  char* error = nullptr;
  const int rc = sqlite3_exec(db,
                              "ALTER TABLE components DROP COLUMN cut_faces;"
                              "ALTER TABLE components DROP COLUMN cap_area;",
                              nullptr, nullptr, &error);
  EXPECT_EQ(rc, SQLITE_OK) << (error ? error : "");
  sqlite3_free(error);
  sqlite3_close(db);
}

TEST(StoreCaps, StoresFromBeforeCapsOpen) {
  ScratchDir scratch;
  const auto dir = make_store(scratch);
  drop_cap_columns(dir);
  {
    const auto store = ComponentStore::open(dir); // read-only: not upgraded
    const auto row = store.find(7);
    ASSERT_TRUE(row);
    EXPECT_TRUE(row->stats.cut_by_border);
    EXPECT_EQ(row->stats.cut_faces, 0);
    EXPECT_EQ(row->stats.cap_area, 0.0);
    EXPECT_EQ(store.query().size(), 2u);
  }
  {
    auto store = ComponentStore::open(dir, OpenMode::read_write); // upgraded, then written
    EXPECT_EQ(store.find(7)->stats.cut_faces, 0);
    LocalSink sink(store, {"second", std::nullopt, 4});
    sink.commit(component(11, box({50, 0, 0}, {59, 3, 3}), store.geometry()));
    sink.close();
  }
  const auto store = ComponentStore::open(dir);
  ASSERT_EQ(store.size(), 3u);
  EXPECT_EQ(mesh::cut_faces_text(store.find(11)->stats.cut_faces), "i+,j-,k-");
  EXPECT_GT(store.find(11)->stats.cap_area, 0.0);
}

TEST(StoreCaps, CommandLineShowsCutFacesAndExportsWithoutCaps) {
  ScratchDir scratch;
  const auto dir = make_store(scratch);
  auto r = geotandem::testing::run_geotandem("store show " + dir.string() + " 7 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j.at("cut_faces"), "i-,k+");
  EXPECT_GT(j.at("cap_area").get<double>(), 0.0);
  r = geotandem::testing::run_geotandem("store show " + dir.string() + " 7");
  EXPECT_NE(r.out.find("faces i-,k+"), std::string::npos) << r.out;
  r = geotandem::testing::run_geotandem("store ls " + dir.string());
  EXPECT_NE(r.out.find("cut i-,k+"), std::string::npos) << r.out;
  for (bool caps : {true, false}) {
    const auto out = scratch.path() / (caps ? "cli_with.obj" : "cli_without.obj");
    r = geotandem::testing::run_geotandem("store export " + dir.string() + " --format obj --out " + out.string() +
                                          (caps ? "" : " --no-caps"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    std::ifstream in(out);
    std::size_t faces = 0;
    for (std::string line; std::getline(in, line);)
      faces += line.rfind("f ", 0) == 0 ? 1 : 0;
    EXPECT_EQ(faces, caps ? 24u : 20u) << caps;
  }
}

} // namespace
} // namespace geotandem::store
