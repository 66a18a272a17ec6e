// The chain description: JSON round trip, the same attribute volume rebuilt from it (checked box by
// box against one built directly with the attribute library), fingerprints, refusals; and a dry
// run that writes nothing.

#include <gtest/gtest.h>

#include <filesystem>

#include "geotandem/attributes/catalog.hpp"
#include "geotandem/builtin/register.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/synth/synthetic.hpp"
#include "geotandem/workflow/chain.hpp"
#include "geotandem/workflow/runner.hpp"
#include "scratch.hpp"

using namespace geotandem;
using namespace geotandem::workflow;
namespace fs = std::filesystem;

namespace {

const char* recipe_text = R"(version: 1
input:
  synthetic: {kind: seismic, shape: [44, 40, 48], seed: 7, snr: 3}
steps:
  - step: envelope
    half_length: 8
    as: env
  - step: rms
    input: input
    window: 5
    as: energy
  - step: product
    inputs: [env, energy]
  - step: extract
    iso: 0.2
  - step: remove_bubbles
output:
  directory: OUT
)";

class Chains : public ::testing::Test {
protected:
  void SetUp() override { builtin::register_builtins(registry); }
  Recipe recipe(const std::string& out_dir = "out") {
    std::string text = recipe_text;
    text.replace(text.find("OUT"), 3, out_dir);
    return parse_recipe(text, "chain.yaml", registry);
  }
  PluginRegistry registry;
};

} // namespace

TEST_F(Chains, DescriptionRoundTripRebuildsTheSameVolume) {
  const ChainDescription original = describe_chain(recipe(), registry);
  ASSERT_EQ(original.steps.size(), 4u); // envelope, rms, product, extract: not the component step
  EXPECT_EQ(original.extract_step().step, "extract");
  EXPECT_EQ(original.extract_step().params.at("iso"), "0.2");
  EXPECT_EQ(original.steps[0].version, registry.get("envelope").version());

  // Through text, as another process would receive it.
  const std::string text = original.to_json().dump();
  const ChainDescription copy = ChainDescription::from_json(nlohmann::json::parse(text));
  EXPECT_EQ(copy.to_json(), original.to_json());
  EXPECT_EQ(copy.fingerprint(), original.fingerprint());

  auto rebuilt = open_chain_volume(copy, registry);
  // Independent oracle: the same chain built with the attribute library and the synthetic module.
  synth::SeismicOptions o;
  o.shape = {44, 40, 48};
  o.seed = 7;
  o.snr = 3;
  std::shared_ptr<const volume::Volume> cube = synth::make_seismic(o);
  auto env = attributes::make_attribute("envelope", {cube}, {{"half_length", std::int64_t{8}}});
  auto energy = attributes::make_attribute("rms", {cube}, {{"window", std::int64_t{5}}});
  auto product = attributes::make_attribute("product", {env, energy});
  ASSERT_EQ(rebuilt->geometry().shape, product->geometry().shape);
  for (volume::Box box : {volume::Box{{0, 0, 0}, {44, 40, 48}}, volume::Box{{3, 4, 5}, {17, 11, 29}},
                          volume::Box{{30, 25, 0}, {44, 40, 48}}, volume::Box{{10, 0, 40}, {11, 40, 48}}}) {
    auto got = rebuilt->read(box);
    auto want = product->read(box);
    ASSERT_EQ(got.size(), box.count());
    EXPECT_EQ(got, want) << box.to_string();
    double energy_sum = 0;
    for (float v : got)
      energy_sum += std::abs(v);
    EXPECT_GT(energy_sum, 0.0) << "a box of zeros would prove nothing: " << box.to_string();
  }
}

TEST_F(Chains, FingerprintFollowsParametersAndVersionsAreChecked) {
  const ChainDescription a = describe_chain(recipe(), registry);
  ChainDescription b = a;
  b.steps[1].params["window"] = "7";
  EXPECT_NE(a.fingerprint(), b.fingerprint());
  EXPECT_NO_THROW(open_chain_volume(b, registry));
  ChainDescription other_version = a;
  other_version.steps[0].version = "99.0";
  try {
    open_chain_volume(other_version, registry);
    FAIL() << "a description of another plugin version was accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("version 99.0"), std::string::npos) << e.what();
  }
  ChainDescription bad_value = a;
  bad_value.steps[1].params["window"] = "4"; // even: refused by the attribute's declaration
  EXPECT_THROW(open_chain_volume(bad_value, registry), InvalidArgument);
  ChainDescription no_extract = a;
  no_extract.steps.pop_back();
  EXPECT_THROW(open_chain_volume(no_extract, registry), InvalidArgument);
  auto j = a.to_json();
  j.erase("input");
  EXPECT_THROW(ChainDescription::from_json(j), FormatError);
  j = a.to_json();
  j["format"] = 2;
  EXPECT_THROW(ChainDescription::from_json(j), FormatError);
  j = a.to_json();
  j["steps"][0].erase("version");
  EXPECT_THROW(ChainDescription::from_json(j), FormatError);
}

TEST_F(Chains, FileInputsAreDescribedByAbsolutePath) {
  auto r = parse_recipe("version: 1\ninput:\n  file: cubes/a.segy\nsteps:\n  - step: extract\n    iso: 1\n",
                        "dir/r.yaml", registry);
  auto d = describe_chain(r, registry);
  fs::path file = d.input.at("file").get<std::string>();
  EXPECT_TRUE(file.is_absolute()) << file;
  EXPECT_EQ(file, fs::absolute("dir/cubes/a.segy").lexically_normal());
}

TEST_F(Chains, DryRunWritesNothing) {
  geotandem::testing::ScratchDir dir;
  const fs::path out = dir.path() / "out";
  Recipe r = recipe(out.string());
  WorkflowSettings settings;
  settings.dry_run = true;
  std::ostringstream log_text;
  Logger log(log_text, LogLevel::info);
  CancelToken cancel;
  RunOutcome outcome = run_workflow(r, registry, settings, log, cancel);
  EXPECT_EQ(outcome.report, "");
  EXPECT_FALSE(fs::exists(out)) << "a dry run created the output directory";
  EXPECT_TRUE(fs::is_empty(dir.path())) << "a dry run wrote into the scratch directory";
  EXPECT_NE(log_text.str().find("nothing was written"), std::string::npos) << log_text.str();
}
