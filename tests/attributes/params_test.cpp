#include <gtest/gtest.h>

#include <set>

#include "fixtures.hpp"
#include "geotandem/attributes/catalog.hpp"
#include "geotandem/attributes/chaos.hpp"
#include "geotandem/attributes/envelope.hpp"
#include "geotandem/attributes/normalise.hpp"
#include "geotandem/attributes/rms.hpp"
#include "geotandem/attributes/semblance.hpp"
#include "geotandem/core/error.hpp"

namespace geotandem::attributes {
namespace {

using testing::cube;

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InvalidArgument& e) {
    return e.what();
  }
  return "(no InvalidArgument)";
}

TEST(Params, EverySpecIsCompleteAndItsDefaultsAreValid) {
  std::set<std::string> names;
  for (const AttributeSpec& spec : builtin_attributes()) {
    EXPECT_TRUE(names.insert(spec.name).second) << spec.name;
    EXPECT_FALSE(spec.summary.empty()) << spec.name;
    EXPECT_GE(spec.inputs, 1);
    for (const ParamSpec& p : spec.params) {
      EXPECT_FALSE(p.help.empty()) << spec.name << "." << p.name;
      if (p.type == ParamType::choice) {
        EXPECT_GE(p.choices.size(), 2u);
      }
    }
    // Resolving nothing yields every parameter at its default, and that passes validation.
    const ParamValues resolved = resolve(spec, {});
    EXPECT_EQ(resolved.size(), spec.params.size());
    for (const ParamSpec& p : spec.params) {
      ASSERT_TRUE(p.default_value.has_value()) << p.name;
      EXPECT_EQ(resolved.at(p.name), parse_param(p, *p.default_value)) << p.name;
      EXPECT_EQ(resolved.at(p.name).type, p.type) << p.name;
      EXPECT_EQ(resolved.at(p.name).text, *p.default_value) << p.name;
    }
  }
  EXPECT_EQ(names, (std::set<std::string>{"envelope", "rms", "semblance", "chaos", "normalise", "product"}));
}

// The declared defaults are read from the options structs (with_defaults): resolving nothing gives
// a default-constructed struct's parameters, and reading those back gives the same struct.
template <class Options> void expect_one_source_of_defaults() {
  const ParamValues declared = resolve(Options::spec(), {});
  EXPECT_EQ(declared, Options{}.to_params()) << Options::spec().name;
  EXPECT_EQ(Options::from_params({}).to_params(), Options{}.to_params()) << Options::spec().name;
  for (const ParamSpec& p : Options::spec().params)
    EXPECT_EQ(p.default_value.value(), Options{}.to_params().at(p.name).text) << p.name;
}

TEST(Params, DefaultsOfTheSpecsAreTheDefaultsOfTheOptions) {
  expect_one_source_of_defaults<EnvelopeOptions>();
  expect_one_source_of_defaults<RmsOptions>();
  expect_one_source_of_defaults<SemblanceOptions>();
  expect_one_source_of_defaults<ChaosOptions>();
  expect_one_source_of_defaults<NormaliseOptions>();
  // Options read from parameters other than the defaults give those parameters back.
  const ChaosOptions marfurt = ChaosOptions::from_params({{"formula", "marfurt"}, {"sigma_t_along", 1.5}});
  EXPECT_EQ(marfurt.formula, ChaosFormula::marfurt);
  EXPECT_EQ(marfurt.sigma_t_along, 1.5);
  EXPECT_EQ(marfurt.sigma_g, ChaosOptions{}.sigma_g);
  const NormaliseOptions fixed = NormaliseOptions::from_params({{"method", "fixed"}, {"scale", 3}});
  EXPECT_EQ(fixed.method, ScaleMethod::fixed);
  EXPECT_EQ(fixed.scale, 3.0);
  EXPECT_EQ(NormaliseOptions::from_params(fixed.to_params()).to_params(), fixed.to_params());
}

TEST(Params, OptionsStructsRefuseWhatTheirDeclarationsRefuse) {
  // validate() checks the struct against the same declarations as a recipe's values.
  EXPECT_NE(message_of([] { ChaosOptions{.sigma_g = 0}.validate(); }).find("'sigma_g' is 0, out of range"),
            std::string::npos);
  EXPECT_NE(message_of([] { SemblanceOptions{.traces = 4}.validate(); }).find("use 3 or 5"), std::string::npos);
  EXPECT_NE(message_of([] { NormaliseOptions{.percentile = 100.5}.validate(); }).find("a real in (0, 100]"),
            std::string::npos);
  EXPECT_NO_THROW(EnvelopeOptions{.half_length = 512}.validate());
  EXPECT_NE(message_of([] {
              EnvelopeOptions{.half_length = 513}.validate();
            }).find("attribute 'envelope': parameter 'half_length' is 513"),
            std::string::npos);
}

TEST(Params, ResolveChecksNamesTypesAndRanges) {
  const AttributeSpec& chaos = ChaosOptions::spec();
  EXPECT_NE(message_of([&] {
              resolve(chaos, {{"sigma", 2.0}});
            }).find("known parameters: formula, sigma_g"),
            std::string::npos);
  EXPECT_NE(message_of([&] {
              resolve(chaos, {{"sigma_g", std::string("wide")}});
            }).find("a real in (0, 20]"),
            std::string::npos);
  EXPECT_NE(message_of([&] {
              resolve(chaos, {{"formula", std::string("curvature")}});
            }).find("one of planarity, marfurt"),
            std::string::npos);
  EXPECT_NE(message_of([&] {
              resolve(RmsOptions::spec(), {{"window", 9.5}});
            }).find("an odd integer in [1, 1001]"),
            std::string::npos);
  // An integer is a valid real.
  const ParamValue two = resolve(chaos, {{"sigma_g", std::int64_t{2}}}).at("sigma_g");
  EXPECT_EQ(two.type, ParamType::real);
  EXPECT_EQ(two.real, 2.0);
}

TEST(Params, RangesPrintTheirOpenAndClosedEnds) {
  const ParamSpec open_closed{.name = "s", .min_value = 0, .max_value = 20, .min_open = true};
  EXPECT_EQ(open_closed.range_text(), "(0, 20]");
  EXPECT_EQ((ParamSpec{.name = "w", .min_value = 1, .max_value = 1001}).range_text(), "[1, 1001]");
  EXPECT_EQ((ParamSpec{.name = "x", .min_value = 0, .min_open = true}).range_text(), "(0, inf)");
  EXPECT_TRUE(open_closed.in_range(20));
  EXPECT_FALSE(open_closed.in_range(0));
  EXPECT_FALSE(open_closed.in_range(std::numeric_limits<double>::quiet_NaN()));
}

TEST(Catalog, MakesEachAttributeWithItsParameters) {
  auto u = cube({16, 16, 32}, [](int i, int j, int k) { return testing::noise(i, j, k); });
  auto chaos = make_attribute("chaos", {u}, {{"formula", std::string("marfurt")}, {"sigma_g", 0.5}});
  ASSERT_NE(dynamic_cast<const Chaos*>(chaos.get()), nullptr);
  EXPECT_EQ(dynamic_cast<const Chaos&>(*chaos).options().formula, ChaosFormula::marfurt);
  EXPECT_EQ(chaos->halo(), (Index3{8, 8, 11}));
  for (const AttributeSpec& spec : builtin_attributes()) {
    std::vector<VolumePtr> inputs(static_cast<std::size_t>(spec.inputs), u);
    auto attribute = make_attribute(spec.name, inputs);
    EXPECT_EQ(attribute->name(), spec.name);
    EXPECT_EQ(attribute->geometry(), u->geometry());
    EXPECT_EQ(attribute->read(Box{{3, 4, 5}, {6, 7, 9}}).size(), 36u);
  }
}

TEST(Catalog, RejectsUnknownNamesAndWrongInputCounts) {
  auto u = cube({4, 4, 8}, [](int, int, int k) { return k; });
  EXPECT_NE(message_of([&] { make_attribute("coherence", {u}); }).find("known attributes: envelope, rms"),
            std::string::npos);
  EXPECT_NE(message_of([&] { make_attribute("product", {u}); }).find("takes 2 inputs, got 1"), std::string::npos);
  EXPECT_NE(message_of([&] {
              make_attribute("product", {u, u}, {{"scale", 2.0}});
            }).find("takes no parameters"),
            std::string::npos);
  EXPECT_NE(message_of([&] {
              make_attribute("rms", {u}, {{"window", std::int64_t{4}}});
            }).find("'window' is 4"),
            std::string::npos);
}

} // namespace
} // namespace geotandem::attributes
