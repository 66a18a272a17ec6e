// The CRS on the command line (issue 54 part 1): --crs checked through OSR and refused naming the
// option, `info` showing it, the store and its runs keeping it, old stores without one, the keys
// unchanged, and `store export --format gpkg`.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "cli_store_support.hpp"
#include "scratch.hpp"

namespace geotandem {
namespace {

using testing::q;
using testing::rows_of;
using testing::run_geotandem;
using testing::ScratchDir;

std::vector<std::uint64_t> keys_of(const std::string& store) {
  std::vector<std::uint64_t> keys;
  for (const auto& row : rows_of(store))
    keys.push_back(row["key"].get<std::uint64_t>());
  return keys;
}

TEST(CrsCli, AWrongCodeIsRefusedNamingTheOption) {
  ScratchDir dir;
  testing::synth(dir.file("a.raw"), 1);
  const std::string cube = q(dir.file("a.raw"));
  for (const std::string& command : {"info " + cube, "extract " + cube + " --iso 0.5 --out " + q(dir.file("s")),
                                     "run-workflow " + q(dir.file("r.yaml"))}) {
    auto r = run_geotandem(command + " --crs EPSG:999999");
    EXPECT_EQ(r.exit_code, 2) << command << ": " << r.err;
    EXPECT_NE(r.err.find("--crs: 'EPSG:999999' is not a coordinate reference system GDAL knows"), std::string::npos)
        << command << ": " << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists(dir.file("s")));
}

TEST(CrsCli, InfoShowsTheCrsOrSaysThereIsNone) {
  ScratchDir dir;
  testing::synth(dir.file("a.raw"), 1);
  auto none = run_geotandem("-q info --no-stats " + q(dir.file("a.raw")));
  ASSERT_EQ(none.exit_code, 0) << none.err;
  EXPECT_NE(none.out.find("crs:        no CRS given"), std::string::npos) << none.out;
  auto given = run_geotandem("-q info --no-stats " + q(dir.file("a.raw")) + " --crs EPSG:2222");
  ASSERT_EQ(given.exit_code, 0) << given.err;
  EXPECT_NE(given.out.find("crs:        NAD83 / Arizona East (ft) (EPSG:2222), x and y in foot"), std::string::npos)
      << given.out;
  EXPECT_NE(given.out.find(" ft x "), std::string::npos) << "bins in the CRS's unit: " << given.out;
  auto json = run_geotandem("-q info --json --no-stats " + q(dir.file("a.raw")) + " --crs EPSG:23031");
  ASSERT_EQ(json.exit_code, 0) << json.err;
  EXPECT_EQ(nlohmann::json::parse(json.out)["crs"]["code"], "EPSG:23031");
}

TEST(CrsCli, TheStoreAndItsRunsKeepTheCrsAndTheKeysStayTheSame) {
  ScratchDir dir;
  testing::synth(dir.file("a.raw"), 2);
  auto plain = run_geotandem("-q extract " + q(dir.file("a.raw")) + " --iso 0.5 --workers 0 --out " + q(dir.file("p")));
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  auto with = run_geotandem("-q extract " + q(dir.file("a.raw")) + " --iso 0.5 --workers 0 --crs EPSG:23031 --out " +
                            q(dir.file("c")));
  ASSERT_EQ(with.exit_code, 0) << with.err;
  EXPECT_EQ(keys_of(dir.file("p")), keys_of(dir.file("c")));
  ASSERT_FALSE(keys_of(dir.file("c")).empty());
  // Blocks in this process, whose surfaces go through the wire form (which carries no CRS) to merge.
  auto blocks = run_geotandem("-q extract " + q(dir.file("a.raw")) +
                              " --iso 0.5 --workers 0 --block-size 16 --crs EPSG:23031 --out " + q(dir.file("b")));
  ASSERT_EQ(blocks.exit_code, 0) << blocks.err;
  EXPECT_EQ(keys_of(dir.file("b")), keys_of(dir.file("c")));
  // With workers, which reopen the cube from the description the manager sends (--crs in it).
  auto workers = run_geotandem("-q extract " + q(dir.file("a.raw")) +
                               " --iso 0.5 --workers 2 --block-size 16 --crs EPSG:23031 --out " + q(dir.file("w")));
  ASSERT_EQ(workers.exit_code, 0) << workers.err;
  EXPECT_EQ(keys_of(dir.file("w")), keys_of(dir.file("c")));
  EXPECT_EQ(nlohmann::json::parse(testing::file_text(dir.file("w/store.json")))["geometry"]["crs"]["code"],
            "EPSG:23031");

  const auto info = nlohmann::json::parse(testing::file_text(dir.file("c/store.json")));
  EXPECT_EQ(info["geometry"]["crs"]["code"], "EPSG:23031");
  EXPECT_FALSE(nlohmann::json::parse(testing::file_text(dir.file("p/store.json")))["geometry"].contains("crs"));
  auto runs = run_geotandem("store runs --json " + q(dir.file("c")));
  ASSERT_EQ(runs.exit_code, 0) << runs.err;
  EXPECT_EQ(nlohmann::json::parse(runs.out)[0]["parameters"]["crs"]["code"], "EPSG:23031");
  auto plain_runs = run_geotandem("store runs --json " + q(dir.file("p")));
  EXPECT_EQ(nlohmann::json::parse(plain_runs.out)[0]["parameters"]["crs"], "no CRS given");

  // Another CRS into the same store is refused; the same one resumes.
  auto other = run_geotandem("-q extract " + q(dir.file("a.raw")) + " --iso 0.5 --workers 0 --crs EPSG:23032 --out " +
                             q(dir.file("c")));
  EXPECT_EQ(other.exit_code, 2) << other.err;
  EXPECT_NE(other.err.find("the store's CRS is ED50 / UTM zone 31N (EPSG:23031), this run's is ED50 / UTM zone 32N "
                           "(EPSG:23032)"),
            std::string::npos)
      << other.err;
  // A store made without one (as before CRSs were kept) opens, says so, and takes the next run's.
  auto key = std::to_string(keys_of(dir.file("p")).front());
  auto show = run_geotandem("store show " + q(dir.file("p")) + " " + key);
  ASSERT_EQ(show.exit_code, 0) << show.err;
  EXPECT_NE(show.out.find("crs:            no CRS given"), std::string::npos) << show.out;
  auto resumed = run_geotandem("-q extract " + q(dir.file("a.raw")) + " --iso 0.5 --workers 0 --crs EPSG:23031 --out " +
                               q(dir.file("p")));
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_EQ(nlohmann::json::parse(testing::file_text(dir.file("p/store.json")))["geometry"]["crs"]["code"],
            "EPSG:23031");
  EXPECT_EQ(keys_of(dir.file("p")), keys_of(dir.file("c")));
}

TEST(CrsCli, StoreExportWritesAGeoPackage) {
  ScratchDir dir;
  testing::synth(dir.file("a.raw"), 3);
  ASSERT_EQ(run_geotandem("-q extract " + q(dir.file("a.raw")) + " --iso 0.5 --workers 0 --crs EPSG:23031 --out " +
                          q(dir.file("s")))
                .exit_code,
            0);
  const auto rows = rows_of(dir.file("s"));
  auto r = run_geotandem("-q store export " + q(dir.file("s")) + " --format gpkg --out " + q(dir.file("b.gpkg")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("exported " + std::to_string(rows.size()) + " components"), std::string::npos) << r.out;
  auto ogr =
      run_geotandem("-q store export " + q(dir.file("s")) + " --format gpkg --per-component --out " + q(dir.file("d")));
  EXPECT_EQ(ogr.exit_code, 2) << ogr.err;
  EXPECT_NE(ogr.err.find("--per-component does not apply"), std::string::npos) << ogr.err;
  // The layers, as ogrinfo (GDAL's own tool) lists them.
  const std::string listing = dir.file("ogrinfo.txt");
  ASSERT_EQ(std::system(("ogrinfo -ro -so " + q(dir.file("b.gpkg")) + " footprints > " + q(listing) + " 2>&1").c_str()),
            0);
  const std::string text = testing::file_text(listing);
  EXPECT_NE(text.find("Feature Count: " + std::to_string(rows.size())), std::string::npos) << text;
  EXPECT_NE(text.find("ED50 / UTM zone 31N"), std::string::npos) << text;
  EXPECT_NE(text.find("azimuth: Real"), std::string::npos) << text;
}

// A recipe run with --crs: the store, the TSurf and GeoPackage exports and the report's map all name
// the CRS.
TEST(CrsCli, ARecipeRunNamesTheCrsEverywhere) {
  ScratchDir dir;
  std::ofstream(dir.file("r.yaml")) << "version: 1\n"
                                       "input:\n"
                                       "  synthetic: {kind: analytic, shape: [64, 56, 48], seed: 4}\n"
                                       "steps:\n"
                                       "  - step: extract\n"
                                       "    iso: 0.5\n"
                                       "  - step: remove_bubbles\n"
                                       "output:\n"
                                       "  directory: " +
                                           q(dir.file("out")) +
                                           "\n"
                                           "  exports:\n"
                                           "    - {format: ts}\n"
                                           "    - {format: gpkg}\n"
                                           "execution: {workers: 1}\n";
  auto r = run_geotandem("-q run-workflow " + q(dir.file("r.yaml")) + " --crs EPSG:23031");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string label = "ED50 / UTM zone 31N (EPSG:23031)";
  EXPECT_EQ(nlohmann::json::parse(testing::file_text(dir.file("out/store/store.json")))["geometry"]["crs"]["code"],
            "EPSG:23031");
  EXPECT_NE(testing::file_text(dir.file("out/bodies.ts")).find("NAME \"" + label + "\""), std::string::npos);
  EXPECT_NE(testing::file_text(dir.file("out/report.html")).find("x, easting (m), " + label), std::string::npos);
  const std::string listing = dir.file("ogrinfo.txt");
  ASSERT_EQ(std::system(
                ("ogrinfo -ro -so " + q(dir.file("out/bodies.gpkg")) + " centroids > " + q(listing) + " 2>&1").c_str()),
            0);
  EXPECT_NE(testing::file_text(listing).find("ED50 / UTM zone 31N"), std::string::npos);
  EXPECT_NE(testing::file_text(listing).find("footprint_area: Real"), std::string::npos) << testing::file_text(listing);
  // Without --crs, the same recipe's outputs say so; its extraction is reused (same chain).
  auto again = run_geotandem("-q run-workflow " + q(dir.file("r.yaml")) + " --fresh");
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_NE(testing::file_text(dir.file("out/bodies.ts")).find("# no CRS given\nNAME Default"), std::string::npos);
  EXPECT_NE(testing::file_text(dir.file("out/report.html")).find("x, easting (m), no CRS given"), std::string::npos);
}

} // namespace
} // namespace geotandem
