// input.crs in recipes and the report's map axes (issue 54 part 1): the CRS is checked through OSR
// while the recipe is read, a wrong code is refused at its line and column, the chain's fingerprint
// (a store's reuse) does not change with it, and the map names it.

#include <gtest/gtest.h>

#include "geotandem/core/error.hpp"
#include "geotandem/volume/crs.hpp"
#include "geotandem/workflow/builtin_steps.hpp"
#include "geotandem/workflow/chain.hpp"
#include "geotandem/workflow/recipe.hpp"
#include "geotandem/workflow/report.hpp"

using namespace geotandem;
using namespace geotandem::workflow;

namespace {

std::string recipe(const std::string& input_extra) {
  return "version: 1\n"
         "input:\n"
         "  synthetic: {kind: analytic, shape: [64, 48, 80], seed: 3}\n" +
         input_extra +
         "steps:\n"
         "  - step: extract\n"
         "    iso: 0.3\n";
}

class CrsRecipes : public ::testing::Test {
protected:
  void SetUp() override { register_builtin_steps(registry); }
  PluginRegistry registry;
};

TEST_F(CrsRecipes, AnEpsgCodeIsCheckedAndKept) {
  Recipe r = parse_recipe(recipe("  crs: \"EPSG:23031\"\n"), "dir/recipe.yaml", registry);
  ASSERT_TRUE(r.input.crs.has_value());
  EXPECT_EQ(r.input.crs->code, "EPSG:23031");
  EXPECT_EQ(r.input.crs->name, "ED50 / UTM zone 31N");
  EXPECT_EQ(r.canonical["input"]["crs"], "EPSG:23031");
  // The CRS changes no component: the chain, whose fingerprint says whether a store is reused,
  // is that of the recipe without it.
  Recipe plain = parse_recipe(recipe(""), "dir/recipe.yaml", registry);
  EXPECT_FALSE(plain.input.crs.has_value());
  EXPECT_EQ(describe_chain(r, registry).fingerprint(), describe_chain(plain, registry).fingerprint());
  EXPECT_FALSE(describe_chain(r, registry).input.contains("crs"));
}

// The workers' copy of the chain carries the recipe's CRS (the runner adds it, as it adds the
// reopen hint): the volume a worker opens from it says the manager's CRS.
TEST_F(CrsRecipes, TheWorkersCopyOfTheChainOpensWithTheCrs) {
  Recipe r = parse_recipe(recipe("  crs: \"EPSG:23031\"\n"), "dir/recipe.yaml", registry);
  nlohmann::json copy = describe_chain(r, registry).to_json();
  EXPECT_TRUE(open_chain(ChainDescription::from_json(copy), registry).result->geometry().crs.empty());
  copy["input"]["crs"] = r.input.crs_text;
  const ChainVolumes volumes = open_chain(ChainDescription::from_json(copy), registry);
  EXPECT_EQ(volumes.input->geometry().crs.code, "EPSG:23031");
  EXPECT_EQ(volumes.result->geometry().crs.code, "EPSG:23031");
  copy["input"]["crs"] = 23031;
  EXPECT_THROW(ChainDescription::from_json(copy), FormatError);
}

TEST_F(CrsRecipes, AWrongCodeIsRefusedAtItsLineAndColumn) {
  try {
    parse_recipe(recipe("  crs: EPSG:999999\n"), "dir/recipe.yaml", registry);
    FAIL() << "accepted";
  } catch (const InvalidArgument& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind("dir/recipe.yaml:4:8: input.crs: 'EPSG:999999' is not a coordinate reference system", 0),
              0u)
        << message;
  }
  try {
    parse_recipe(recipe(""), "dir/recipe.yaml", registry, {"input.crs=EPSG:4326"});
    FAIL() << "accepted";
  } catch (const InvalidArgument& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind("--set input.crs=EPSG:4326: input.crs: 'EPSG:4326' is a geographic CRS", 0), 0u) << message;
  }
}

// input.crs is a declared key of the input section: a misspelling gets its did-you-mean.
TEST_F(CrsRecipes, AMisspelledCrsKeyIsNamedWithTheRightOne) {
  try {
    parse_recipe(recipe("  crss: \"EPSG:23031\"\n"), "dir/recipe.yaml", registry);
    FAIL() << "accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("dir/recipe.yaml:4:3: unknown key 'crss' in input (did you mean 'crs'?)"),
              std::string::npos)
        << e.what();
  }
}

TEST(ReportMap, TheAxesNameTheCrsAndItsUnit) {
  ReportSurvey survey;
  survey.known = true;
  survey.corners = {{{431000, 4612000}, {433000, 4612000}, {433000, 4614500}, {431000, 4614500}}};
  survey.crs = "NAD83 / Arizona East (ft) (EPSG:2222)";
  survey.xy_unit = "ft";
  ReportBody body;
  body.key = 7;
  body.footprint = {{431500, 4612500}, {432000, 4612500}, {432000, 4613000}};
  const std::string svg = svg_body_map(survey, {body});
  EXPECT_NE(svg.find("x, easting (ft), NAD83 / Arizona East (ft) (EPSG:2222)"), std::string::npos) << svg;
  EXPECT_NE(svg.find("y, northing (ft)"), std::string::npos);
  EXPECT_NE(svg.find(">432000<"), std::string::npos) << "a tick value in map coordinates";
  EXPECT_NE(svg.find(" ft</text></g>"), std::string::npos) << "the scale bar in the CRS's unit";
  survey.crs = volume::kNoCrs;
  survey.xy_unit = "m";
  EXPECT_NE(svg_body_map(survey, {body}).find("x, easting (m), no CRS given"), std::string::npos);
}

} // namespace
