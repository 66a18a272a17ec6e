// The extraction's options (extraction_options.hpp): one value, its declarations read from one
// table, its JSON codec, and the leaf size block_size 0 stands for.
#include <gtest/gtest.h>

#include <limits>

#include "geotandem/core/error.hpp"
#include "geotandem/tandem/extraction_options.hpp"

namespace geotandem::tandem {
namespace {

TEST(ExtractionOptions, DeclaredDefaultsAreTheValuesDefaults) {
  const ExtractionOptions d;
  const auto& specs = extraction_params();
  ASSERT_EQ(specs.size(), extraction_fields().size());
  // iso is required: a recipe and the command line must give it.
  EXPECT_FALSE(specs.front().default_value.has_value());
  ParamValues values;
  values["iso"] = ParamValue(0.0);
  for (const auto& spec : specs)
    if (spec.default_value) values[spec.name] = parse_param(spec, *spec.default_value);
  EXPECT_EQ(options_from_params(values), d);
  // And the defaults the collapse loop has (SimplifyOptions), not other literals.
  EXPECT_EQ(values.at("max_error").real, SimplifyOptions{}.max_error);
  EXPECT_EQ(values.at("isotropy").real, SimplifyOptions{}.isotropy);
  EXPECT_EQ(values.at("extended_time_lag").boolean, SimplifyOptions{}.extended_time_lag);
  EXPECT_EQ(values.at("block_size").integer, 128);
  EXPECT_EQ(values.at("axis").text, "i");
  EXPECT_EQ(values.at("mode").text, "tandem-dump");
}

TEST(ExtractionOptions, JsonRoundTripKeepsEveryValue) {
  ExtractionOptions o;
  o.iso = 0.6f;
  o.max_error = 0.25;
  o.isotropy = 0.7;
  o.axis = 2;
  o.block_size = 0;
  o.mode = ExtractMode::brute;
  o.extended_time_lag = false;
  const nlohmann::json j = to_json(o);
  EXPECT_EQ(j.at("iso").get<double>(), 0.6) << "a float isovalue as the decimal a user wrote";
  EXPECT_EQ(j.at("axis"), "k");
  EXPECT_EQ(j.at("mode"), "brute");
  EXPECT_EQ(j.at("block_size"), 0);
  EXPECT_EQ(options_from_json(j), o);
  EXPECT_EQ(options_from_json(nlohmann::json::parse(j.dump())), o) << "through its text too";
  // Every declared option is in the JSON, and nothing else.
  EXPECT_EQ(j.size(), extraction_fields().size());
}

TEST(ExtractionOptions, JsonOfAnotherVersionIsRefusedByName) {
  nlohmann::json j = to_json(ExtractionOptions{});
  auto unknown = j;
  unknown["max_eror"] = 1.0;
  try {
    (void)options_from_json(unknown);
    FAIL() << "an unknown key was accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(e.message().find("max_eror"), std::string::npos) << e.message();
    EXPECT_NE(e.hint().find("max_error"), std::string::npos) << e.hint();
  }
  auto missing = j;
  missing.erase("isotropy");
  EXPECT_THROW((void)options_from_json(missing), InvalidArgument);
  auto wrong_type = j;
  wrong_type["block_size"] = "64";
  EXPECT_THROW((void)options_from_json(wrong_type), InvalidArgument);
  auto out_of_range = j;
  out_of_range["isotropy"] = 2.0;
  EXPECT_THROW((void)options_from_json(out_of_range), InvalidArgument);
  auto tiny_block = j;
  tiny_block["block_size"] = 4;
  EXPECT_THROW((void)options_from_json(tiny_block), InvalidArgument);
}

TEST(ExtractionOptions, ValidateRefusesWhatTheDeclarationsRefuse) {
  ExtractionOptions o;
  EXPECT_NO_THROW(o.validate());
  o.block_size = 7;
  EXPECT_THROW(o.validate(), InvalidArgument);
  o.block_size = 0;
  EXPECT_NO_THROW(o.validate());
  o.max_error = 0;
  EXPECT_THROW(o.validate(), InvalidArgument);
  o.max_error = 0.5;
  o.axis = 3;
  EXPECT_THROW(o.validate(), InvalidArgument);
  o.axis = 1;
  o.iso = std::numeric_limits<float>::infinity();
  EXPECT_THROW(o.validate(), InvalidArgument);
}

TEST(ExtractionOptions, BlockSizeZeroIsOneLeafOfTheWholeCube) {
  ExtractionOptions o;
  o.block_size = 0;
  EXPECT_EQ(leaf_size(o, {160, 144, 96}), 159);
  o.block_size = 64;
  EXPECT_EQ(leaf_size(o, {160, 144, 96}), 64);
}

TEST(ExtractionOptions, LoopOptionsCarryEveryOption) {
  ExtractionOptions o;
  o.iso = 1.5f;
  o.axis = 1;
  o.max_error = 0.3;
  o.isotropy = 0.2;
  o.extended_time_lag = false;
  o.mode = ExtractMode::tandem;
  const TandemOptions t = loop_options(o);
  EXPECT_EQ(t.iso, 1.5f);
  EXPECT_EQ(t.axis, 1);
  EXPECT_EQ(t.simplify.max_error, 0.3);
  EXPECT_EQ(t.simplify.isotropy, 0.2);
  EXPECT_FALSE(t.simplify.extended_time_lag);
  EXPECT_FALSE(t.dump) << "the plain tandem keeps its components to the end of the block";
  o.mode = ExtractMode::tandem_dump;
  EXPECT_TRUE(loop_options(o).dump);
}

} // namespace
} // namespace geotandem::tandem
