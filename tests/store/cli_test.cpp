// `geotandem store ...` run as a child process against a store made here from formulas.

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "fixtures.hpp"
#include "geotandem/store/local_sink.hpp"
#include "scratch.hpp"

namespace geotandem::store {
namespace {

using geotandem::testing::run_geotandem;
using geotandem::testing::ScratchDir;

class StoreCli : public ::testing::Test {
protected:
  void SetUp() override {
    dir_ = scratch_.path() / "store";
    auto store = ComponentStore::create(dir_, testing::test_geometry());
    run_ = store.begin_run(R"({"command": "extract", "threshold": 0.7})");
    LocalSink sink(store, {"local", run_, 16});
    for (std::uint64_t key = 1; key <= 30; ++key)
      sink.commit(testing::make_component(key, testing::test_geometry()));
    sink.close();
    store.end_run(run_, R"({"collapses": 4321})");
    store.save_selection("big", {30, 3, 17}, R"({"step": "remove_bubbles"})");
    rows_ = store.query();
  }

  std::string store_arg() const { return "'" + dir_.string() + "'"; }

  ScratchDir scratch_;
  std::filesystem::path dir_;
  std::int64_t run_ = 0;
  std::vector<ComponentRow> rows_;
};

TEST_F(StoreCli, LsJsonMatchesTheIndexAndFilters) {
  auto r = run_geotandem("store ls " + store_arg() + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto all = nlohmann::json::parse(r.out);
  ASSERT_EQ(all.size(), rows_.size());
  for (std::size_t i = 0; i < rows_.size(); ++i) {
    EXPECT_EQ(all[i]["key"].get<std::uint64_t>(), rows_[i].key);
    EXPECT_EQ(all[i]["volume"].get<double>(), rows_[i].stats.volume);
    EXPECT_EQ(all[i]["azimuth"].get<double>(), rows_[i].stats.azimuth);
    EXPECT_EQ(all[i]["triangle_count"].get<std::uint64_t>(), rows_[i].location.triangle_count);
    EXPECT_EQ(all[i]["run"].get<std::int64_t>(), run_);
    EXPECT_EQ(all[i]["closed"].get<bool>(), rows_[i].stats.closed);
  }
  // Filters, checked against the rows: wrap-around azimuth and a volume floor, largest first.
  r = run_geotandem("store ls " + store_arg() + " --azimuth 150:30 --min-volume 1 --sort volume --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto some = nlohmann::json::parse(r.out);
  std::size_t expected = 0;
  for (const auto& row : rows_)
    expected += (row.stats.azimuth >= 150 || row.stats.azimuth <= 30) && row.stats.volume >= 1;
  ASSERT_EQ(some.size(), expected);
  ASSERT_GT(expected, 1u);
  for (std::size_t i = 1; i < some.size(); ++i)
    EXPECT_GE(some[i - 1]["volume"], some[i]["volume"]);
  r = run_geotandem("store ls " + store_arg() + " --selection big --sort selection --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto selected = nlohmann::json::parse(r.out);
  ASSERT_EQ(selected.size(), 3u);
  EXPECT_EQ(selected[0]["key"], 30);
  EXPECT_EQ(selected[2]["key"], 17);
}

TEST_F(StoreCli, LsTableListsKeysAndCounts) {
  auto r = run_geotandem("store ls " + store_arg() + " --limit 5");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("key"), std::string::npos);
  EXPECT_NE(r.out.find("azimuth"), std::string::npos);
  EXPECT_NE(r.out.find("# 5 of 30 components"), std::string::npos) << r.out;
  std::istringstream lines(r.out);
  std::string header, line;
  std::getline(lines, header);
  std::getline(lines, line);
  std::istringstream first(line);
  std::uint64_t key = 0;
  first >> key;
  EXPECT_EQ(key, rows_[0].key);
  EXPECT_NE(line.find(std::to_string(rows_[0].location.triangle_count)), std::string::npos) << line;
}

TEST_F(StoreCli, ShowPrintsEveryIndexField) {
  const auto& row = rows_[4];
  auto r = run_geotandem("store show " + store_arg() + " " + std::to_string(row.key) + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  for (const char* field : {"key",      "vertex_count", "triangle_count", "volume",        "area",
                            "centroid", "box_min",      "box_max",        "obb",           "azimuth",
                            "dip",      "elongation",   "closed",         "cut_by_border", "cut_faces",
                            "cap_area", "run",          "shard",          "offset",        "length",
                            "checksum"})
    EXPECT_TRUE(j.contains(field)) << field;
  EXPECT_EQ(j["box_max"][2].get<double>(), row.stats.box_max[2]);
  EXPECT_EQ(j["offset"].get<std::uint64_t>(), row.location.offset);
  r = run_geotandem("store show " + store_arg() + " " + std::to_string(row.key));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* label : {"volume:", "azimuth:", "dip:", "elongation:", "obb axis 2:", "record:"})
    EXPECT_NE(r.out.find(label), std::string::npos) << label << "\n" << r.out;
}

TEST_F(StoreCli, ExportWritesTheSelectedComponents) {
  auto out = scratch_.path() / "big.obj";
  auto r =
      run_geotandem("-q store export " + store_arg() + " --format obj --selection big --out '" + out.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("exported 3 components"), std::string::npos) << r.out;
  std::ifstream in(out);
  std::size_t objects = 0;
  for (std::string line; std::getline(in, line);)
    objects += line.rfind("o geobody_", 0) == 0;
  EXPECT_EQ(objects, 3u);
  auto dir = scratch_.path() / "each";
  r = run_geotandem("-q store export " + store_arg() + " --format ts --per-component --limit 4 --out '" + dir.string() +
                    "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (std::size_t i = 0; i < 4; ++i)
    EXPECT_TRUE(std::filesystem::exists(dir / ("geobody_" + std::to_string(rows_[i].key) + ".ts")));
}

TEST_F(StoreCli, RunsAndSelectionsAreListed) {
  auto r = run_geotandem("store runs " + store_arg() + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto runs = nlohmann::json::parse(r.out);
  ASSERT_EQ(runs.size(), 1u);
  EXPECT_EQ(runs[0]["components"], 30);
  EXPECT_EQ(runs[0]["parameters"]["threshold"], 0.7);
  EXPECT_EQ(runs[0]["statistics"]["collapses"], 4321);
  r = run_geotandem("store runs " + store_arg());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("30 components"), std::string::npos) << r.out;
  r = run_geotandem("store selections " + store_arg());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("big: 3 components"), std::string::npos) << r.out;
}

TEST_F(StoreCli, ErrorsNameWhatAndWhere) {
  auto missing = scratch_.path() / "no-such-store";
  auto r = run_geotandem("store ls '" + missing.string() + "'");
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_NE(r.err.find(missing.string()), std::string::npos) << r.err;

  auto plain = scratch_.path() / "plain";
  std::filesystem::create_directories(plain);
  r = run_geotandem("store ls '" + plain.string() + "'");
  EXPECT_EQ(r.exit_code, 4);
  EXPECT_NE(r.err.find("not a geotandem store"), std::string::npos) << r.err;

  r = run_geotandem("store ls " + store_arg() + " --azimuth 30-60");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("30-60"), std::string::npos) << r.err;
  r = run_geotandem("store ls " + store_arg() + " --box 1,2,3");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("x0,y0,z0,x1,y1,z1"), std::string::npos) << r.err;
  r = run_geotandem("store ls " + store_arg() + " --sort size");
  EXPECT_EQ(r.exit_code, 2);
  r = run_geotandem("store ls " + store_arg() + " --selection nope");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("big"), std::string::npos) << "known selections are suggested: " << r.err;

  r = run_geotandem("store show " + store_arg() + " 999999");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("999999"), std::string::npos) << r.err;
  r = run_geotandem("store show " + store_arg() + " twelve");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("twelve"), std::string::npos) << r.err;

  r = run_geotandem("store export " + store_arg() + " --format stl --out '" + (scratch_.path() / "x").string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("stl"), std::string::npos) << r.err;
  r = run_geotandem("-q store export " + store_arg() + " --format ply --min-volume 1e30 --out '" +
                    (scratch_.path() / "none.ply").string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("no component"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(scratch_.path() / "none.ply"));
}

} // namespace
} // namespace geotandem::store
