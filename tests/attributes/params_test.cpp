#include <gtest/gtest.h>

#include <set>

#include "fixtures.hpp"
#include "geotandem/attributes/catalog.hpp"
#include "geotandem/attributes/chaos.hpp"
#include "geotandem/attributes/rms.hpp"
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
    for (const ParamSpec& p : spec.params)
      EXPECT_EQ(resolved.at(p.name), p.default_value) << p.name;
  }
  EXPECT_EQ(names, (std::set<std::string>{"envelope", "rms", "semblance", "chaos", "normalise", "product"}));
}

TEST(Params, DefaultsOfTheSpecsAreTheDefaultsOfTheOptions) {
  EXPECT_EQ(resolve(ChaosOptions::spec(), {}), ChaosOptions{}.to_params());
  EXPECT_EQ(resolve(RmsOptions::spec(), {}), RmsOptions{}.to_params());
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
  EXPECT_EQ(get_real(resolve(chaos, {{"sigma_g", std::int64_t{2}}}), "sigma_g"), 2.0);
}

TEST(Params, RangesPrintTheirOpenAndClosedEnds) {
  EXPECT_EQ((ParamRange{0, 20, true}).to_string(), "(0, 20]");
  EXPECT_EQ((ParamRange{1, 1001}).to_string(), "[1, 1001]");
  EXPECT_EQ((ParamRange{0, std::numeric_limits<double>::infinity(), true}).to_string(), "(0, inf)");
  EXPECT_TRUE((ParamRange{0, 20, true}).contains(20));
  EXPECT_FALSE((ParamRange{0, 20, true}).contains(0));
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
