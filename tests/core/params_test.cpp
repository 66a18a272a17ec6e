// The one parameter model: the same declaration checks a recipe's text and a C++ caller's typed
// value, with the same messages.

#include <gtest/gtest.h>

#include <functional>
#include <limits>

#include "geotandem/core/error.hpp"
#include "geotandem/core/params.hpp"

namespace geotandem {
namespace {

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InvalidArgument& e) {
    return e.what();
  }
  return "(no InvalidArgument)";
}

const ParamSpec window{.name = "window",
                       .type = ParamType::integer,
                       .default_value = "9",
                       .help = "window length",
                       .min_value = 1,
                       .max_value = 1001,
                       .odd = true,
                       .unit = "samples"};
const ParamSpec sigma{
    .name = "sigma", .type = ParamType::real, .default_value = "1", .min_value = 0, .max_value = 20, .min_open = true};
const ParamSpec formula{
    .name = "formula", .type = ParamType::choice, .default_value = "planarity", .choices = {"planarity", "marfurt"}};

TEST(Params, TextAndTypedValuesGiveTheSameValue) {
  EXPECT_EQ(parse_param(window, "11"), check_param(window, 11));
  EXPECT_EQ(parse_param(window, "11").text, "11");
  EXPECT_EQ(parse_param(sigma, "2.50"), check_param(sigma, 2.5));
  EXPECT_EQ(parse_param(sigma, "2.50").text, "2.50"); // as the recipe wrote it
  EXPECT_EQ(check_param(sigma, 2.5).text, "2.5");
  // An integer is a valid real; a word is a valid choice.
  const ParamValue two = check_param(sigma, std::int64_t{2});
  EXPECT_EQ(two.type, ParamType::real);
  EXPECT_EQ(two.real, 2.0);
  EXPECT_EQ(check_param(formula, "marfurt").type, ParamType::choice);
  EXPECT_EQ(parse_param(formula, "marfurt"), ParamValue("marfurt"));
  EXPECT_NE(ParamValue(2.0), ParamValue(2));
}

TEST(Params, EveryRefusalNamesTheParameterTheValueAndWhatIsAllowed) {
  for (const auto& m : {message_of([] { parse_param(window, "8"); }), message_of([] { check_param(window, 8); })}) {
    EXPECT_NE(m.find("parameter 'window' is 8, not odd: it must be an odd integer in [1, 1001]"), std::string::npos)
        << m;
    EXPECT_NE(m.find("use 7 or 9"), std::string::npos) << m;
  }
  for (const auto& m : {message_of([] { parse_param(sigma, "0"); }), message_of([] { check_param(sigma, 0.0); })}) {
    EXPECT_NE(m.find("parameter 'sigma' is 0, out of range: it must be a real in (0, 20]"), std::string::npos) << m;
    EXPECT_NE(m.find("use a value above 0 and at most 20"), std::string::npos) << m;
  }
  EXPECT_NE(message_of([] { parse_param(window, "9.5"); }).find("'window' is '9.5', not an odd integer in [1, 1001]"),
            std::string::npos);
  EXPECT_NE(message_of([] { check_param(window, 9.5); }).find("'window' is '9.5', not an odd integer"),
            std::string::npos);
  EXPECT_NE(message_of([] { parse_param(sigma, "nan"); }).find("not a real in (0, 20]"), std::string::npos);
  EXPECT_NE(message_of([] { check_param(sigma, std::numeric_limits<double>::infinity()); }).find("'sigma' is 'inf'"),
            std::string::npos);
  EXPECT_NE(message_of([] { parse_param(formula, "marfut"); }).find("did you mean 'marfurt'?"), std::string::npos);
  EXPECT_NE(message_of([] { check_param(formula, 3); }).find("not one of planarity, marfurt"), std::string::npos);
  EXPECT_NE(message_of([] {
              check_param(sigma, 50.0, "attribute 'chaos'");
            }).find("attribute 'chaos': parameter 'sigma' is 50, out of range"),
            std::string::npos);
}

TEST(Params, ResolveFillsDefaultsAndRefusesUnknownAndMissingParameters) {
  const std::vector<ParamSpec> specs{window, sigma, formula};
  const ParamValues all = resolve_params(specs, {{"sigma", 3}});
  ASSERT_EQ(all.size(), 3u);
  EXPECT_EQ(all.at("window").integer, 9);
  EXPECT_EQ(all.at("sigma").real, 3.0);
  EXPECT_EQ(all.at("formula").text, "planarity");
  EXPECT_EQ(all, (ParamValues{{"window", 9}, {"sigma", 3.0}, {"formula", "planarity"}}));
  EXPECT_EQ(to_string(all), "formula=planarity, sigma=3, window=9");
  EXPECT_EQ(default_values(specs), resolve_params(specs, {}));
  const std::string unknown = message_of([&] { resolve_params(specs, {{"sigmma", 1.0}}, "attribute 'x'"); });
  EXPECT_NE(unknown.find("attribute 'x' has no parameter 'sigmma'"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("did you mean 'sigma'? known parameters: window, sigma, formula"), std::string::npos)
      << unknown;
  ParamSpec required = sigma;
  required.default_value.reset();
  EXPECT_NE(message_of([&] { resolve_params({required}, {}); }).find("parameter 'sigma' is required"),
            std::string::npos);
  EXPECT_NE(message_of([&] { default_values({required}); }).find("has no default"), std::string::npos);
  EXPECT_NE(message_of([] { resolve_params({}, {{"scale", 2.0}}); }).find("takes no parameters"), std::string::npos);
}

TEST(Params, RangesAndValidValuesRead) {
  EXPECT_EQ(window.range_text(), "[1, 1001]");
  EXPECT_EQ(sigma.range_text(), "(0, 20]");
  EXPECT_EQ((ParamSpec{.name = "a", .max_value = 5}).range_text(), "(-inf, 5]");
  EXPECT_EQ((ParamSpec{.name = "b", .type = ParamType::integer}).valid_values(), "an integer");
  EXPECT_EQ((ParamSpec{.name = "c", .type = ParamType::boolean}).valid_values(), "true or false");
  EXPECT_TRUE(sigma.in_range(20));
  EXPECT_FALSE(sigma.in_range(0));
  EXPECT_FALSE(sigma.in_range(std::numeric_limits<double>::quiet_NaN()));
  EXPECT_EQ(number_text(0.1), "0.1");
  EXPECT_EQ(number_text(-std::numeric_limits<double>::infinity()), "-inf");
}

TEST(Params, SizesAndDurationsAreReadIntoTheirUnits) {
  ParamSpec memory{.name = "memory", .type = ParamType::text, .min_value = 1};
  memory.form = ParamSpec::Form::size_mib;
  EXPECT_EQ(parse_param(memory, "2048M").integer, 2048);
  EXPECT_EQ(parse_param(memory, "4G").integer, 4096);
  EXPECT_EQ(parse_param(memory, "1.5G").integer, 1536);
  EXPECT_EQ(parse_param(memory, "512").integer, 512);
  EXPECT_EQ(parse_param(memory, "2T").integer, 2 * 1024 * 1024);
  EXPECT_EQ(check_param(memory, ParamValue("3G")).integer, 3072); // a typed caller's text, the same way
  for (const char* bad : {"lots", "G", "4Q", "-5M", "", "nanG", "1e300G"})
    EXPECT_NE(message_of([&] { parse_param(memory, bad); }).find("not a size such as 2048M or 4G"), std::string::npos)
        << bad;
  EXPECT_NE(message_of([&] { parse_param(memory, "0"); }).find("is 0, out of range"), std::string::npos);

  ParamSpec walltime{.name = "walltime", .type = ParamType::text, .min_value = 1};
  walltime.form = ParamSpec::Form::duration_s;
  EXPECT_EQ(parse_param(walltime, "01:30:00").integer, 5400);
  EXPECT_EQ(parse_param(walltime, "1:30").integer, 5400); // hh:mm
  EXPECT_EQ(parse_param(walltime, "90").integer, 5400);   // minutes
  EXPECT_EQ(parse_param(walltime, "0:00:07").integer, 7);
  for (const char* bad : {"1:75", "1:30:60", "1:2:3:4", "1h", "", ":30", "-5", "1.5"})
    EXPECT_NE(message_of([&] { parse_param(walltime, bad); }).find("not a duration"), std::string::npos) << bad;
  EXPECT_NE(message_of([&] { parse_param(walltime, "0"); }).find("out of range"), std::string::npos);
}

TEST(Params, AListsEntriesAreDeclaredLikeAParameter) {
  ParamSpec shape{.name = "shape", .type = ParamType::text, .min_value = 40, .max_value = 100000};
  shape.list = true;
  shape.item_type = ParamType::integer;
  shape.list_length = 3;
  const ParamSpec entry = shape.entry();
  EXPECT_EQ(entry.type, ParamType::integer);
  EXPECT_FALSE(entry.list);
  EXPECT_EQ(parse_param(entry, "64").integer, 64);
  EXPECT_NE(message_of([&] { parse_param(entry, "8"); }).find("out of range: it must be an integer in [40, 100000]"),
            std::string::npos);
  EXPECT_EQ(shape.valid_values(), "a list of 3 entries, each an integer in [40, 100000]");
  ParamSpec words{.name = "extra_args", .type = ParamType::text};
  words.list = true;
  EXPECT_EQ(words.valid_values(), "a list of words");
}

} // namespace
} // namespace geotandem
