// The fused chain's shared input (framework/workflow/src/shared_input.hpp): every attribute of the
// catalogue read through open_chain, in the slabs an extraction asks for (leaf blocks of cells,
// their sections a few at a time, blocks touching the cube's faces and each other), equals the
// same chain built directly with the attribute library and read as one whole cube, bit for bit;
// and the input is generated once per read of the result, not once per attribute reading it.
// Missing samples filled by the recipe (`nan: fill`) are dead samples to the attributes and outside
// in the result.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "geotandem/attributes/catalog.hpp"
#include "geotandem/builtin/register.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/synth/synthetic.hpp"
#include "geotandem/volume/io.hpp"
#include "geotandem/workflow/chain.hpp"
#include "scratch.hpp"
#include "shared_input.hpp"

using namespace geotandem;
using namespace geotandem::workflow;

namespace {

// chaos, envelope -> normalise, rms, semblance: every attribute, all feeding the extraction.
std::string recipe_text(const std::string& normalise_method) {
  return R"(version: 1
input:
  synthetic: {kind: seismic, shape: [44, 40, 52], seed: 5, snr: 3}
steps:
  - step: chaos
    input: input
    sigma_t_across: 2
  - step: envelope
    input: input
    half_length: 8
  - step: normalise
    as: bright
    input: envelope
    method: )" +
         normalise_method + R"(
  - step: product
    as: facies
    inputs: [chaos, bright]
  - step: rms
    input: input
    window: 5
  - step: semblance
    input: input
  - step: product
    as: coherent
    inputs: [rms, semblance]
  - step: product
    as: result
    inputs: [facies, coherent]
  - step: extract
    input: result
    iso: 0.2
output:
  directory: out
)";
}

std::shared_ptr<const volume::Volume> oracle(const std::string& normalise_method) {
  synth::SeismicOptions o;
  o.shape = {44, 40, 52};
  o.seed = 5;
  o.snr = 3;
  std::shared_ptr<const volume::Volume> cube = synth::make_seismic(o);
  using attributes::make_attribute;
  auto chaos = make_attribute("chaos", {cube}, {{"sigma_t_across", 2.0}});
  auto envelope = make_attribute("envelope", {cube}, {{"half_length", std::int64_t{8}}});
  auto bright = make_attribute("normalise", {envelope}, {{"method", normalise_method}});
  auto facies = make_attribute("product", {chaos, bright});
  auto rms = make_attribute("rms", {cube}, {{"window", std::int64_t{5}}});
  auto semblance = make_attribute("semblance", {cube});
  auto coherent = make_attribute("product", {rms, semblance});
  return make_attribute("product", {facies, coherent});
}

// The sample boxes an extraction reads: leaf blocks of `leaf` cells along i and j (whole along k),
// each read in slabs of `sections` cross-sections along i, as tandem's SlabReader does.
std::vector<volume::Box> slab_boxes(const volume::Index3& shape, std::int64_t leaf, std::int64_t sections) {
  std::vector<volume::Box> boxes;
  for (std::int64_t i0 = 0; i0 < shape[0] - 1; i0 += leaf)
    for (std::int64_t j0 = 0; j0 < shape[1] - 1; j0 += leaf) {
      const std::int64_t i1 = std::min(i0 + leaf, shape[0] - 1) + 1, j1 = std::min(j0 + leaf, shape[1] - 1) + 1;
      for (std::int64_t s = i0; s < i1; s += sections)
        boxes.push_back({{s, j0, 0}, {std::min(s + sections, i1), j1, shape[2]}});
    }
  return boxes;
}

class SharedInputs : public ::testing::TestWithParam<std::string> {
protected:
  void SetUp() override { builtin::register_builtins(registry); }
  PluginRegistry registry;
};

} // namespace

TEST_P(SharedInputs, SlabsOfTheFusedChainEqualTheWholeCubeBitForBit) {
  const Recipe recipe = parse_recipe(recipe_text(GetParam()), "shared.yaml", registry);
  const ChainVolumes chain = open_chain(describe_chain(recipe, registry), registry);
  const auto want_volume = oracle(GetParam());
  const volume::Index3 shape = want_volume->geometry().shape;
  const std::vector<float> whole = want_volume->read(want_volume->geometry().bounds());
  double magnitude = 0.0;
  for (float v : whole)
    magnitude += std::abs(v);
  ASSERT_GT(magnitude, 0.0) << "a cube of zeros would prove nothing";
  for (const auto& [leaf, sections] : {std::pair<std::int64_t, std::int64_t>{16, 5}, {13, 1}, {43, 44}}) {
    for (const volume::Box& box : slab_boxes(shape, leaf, sections)) {
      const std::vector<float> got = chain.result->read(box);
      std::vector<float> cut(box.count());
      volume::copy_region(whole.data(), want_volume->geometry().bounds(), cut.data(), box, box);
      ASSERT_EQ(0, std::memcmp(got.data(), cut.data(), cut.size() * sizeof(float)))
          << "normalise " << GetParam() << ", leaves of " << leaf << ", slab " << box.to_string();
    }
  }
}

TEST_P(SharedInputs, TheInputIsFetchedOncePerReadOfTheResult) {
  const Recipe recipe = parse_recipe(recipe_text(GetParam()), "shared.yaml", registry);
  const ChainVolumes chain = open_chain(describe_chain(recipe, registry), registry);
  const auto* prefetching = dynamic_cast<const detail::PrefetchingResult*>(chain.result.get());
  ASSERT_NE(prefetching, nullptr) << "the chain's result does not share its input";
  const volume::Index3 halo = chain.result->source_halo();
  EXPECT_GT(halo[0], 0);
  EXPECT_GT(halo[2], 8); // envelope's half length at least
  if (GetParam() == "percentile") chain.result->read(volume::Box{{0, 0, 0}, {1, 1, 1}}); // the scale's sample
  const auto before = prefetching->input().counts();
  std::int64_t grown = 0, read = 0;
  for (const volume::Box& box : slab_boxes(chain.result->geometry().shape, 16, 6)) {
    chain.result->read(box);
    grown += box.grown(halo).intersection(chain.result->geometry().bounds()).count();
    read += box.count();
  }
  const auto after = prefetching->input().counts();
  // One fetch of box + halo per read; every attribute (four read the input) served from it.
  EXPECT_EQ(after.fetched - before.fetched, grown);
  EXPECT_EQ(after.direct, before.direct) << "an attribute read the input outside the fetched box";
  EXPECT_GT(after.served - before.served, 3 * read);
  // The fetched box ends with the read of the result (its storage stays for the next fetch): a
  // read of the input afterwards goes to the input, never to values left from the last box.
  const volume::Box inside{{2, 3, 4}, {6, 7, 9}};
  const std::vector<float> direct = prefetching->input().read(inside);
  EXPECT_EQ(prefetching->input().counts().direct - after.direct, inside.count());
  EXPECT_EQ(prefetching->input().counts().served, after.served);
  EXPECT_EQ(direct.size(), static_cast<std::size_t>(inside.count()));
}

INSTANTIATE_TEST_SUITE_P(Normalise, SharedInputs, ::testing::Values("percentile", "fixed"));

namespace {

// The facies chain of the quickstart recipe on `file`, extracting `extracted`.
std::string facies_recipe(const std::string& file, const std::string& nan, const std::string& extracted,
                          const std::string& more_input = "") {
  return R"(version: 1
input: {file: ")" +
         file + R"(", nan: )" + nan + more_input + R"(}
steps:
  - {step: chaos, input: input, sigma_t_across: 2}
  - {step: envelope, input: input, half_length: 8}
  - {step: normalise, as: bright, input: envelope, method: percentile}
  - {step: product, as: facies, inputs: [chaos, bright]}
  - {step: extract, input: )" +
         extracted + R"(, iso: 0.2}
output:
  directory: out
)";
}

} // namespace

// A cube whose traces are missing in a corner (NaN, as a survey's outline leaves them) and with one
// infinite sample, read with `nan: fill`. Oracle: the same chain built with the attribute library
// on the same cube with zeros there (dead traces). Every sample of the result away from the
// missing ones equals it bit for bit; every missing one is the lowest float, outside every body.
// Before, the attributes saw the fill's lowest float: the envelope went to -inf, the normalisation
// scale was not finite, and the run stopped with advice to use the fill it was using.
TEST(MissingSamples, FilledTheyAreDeadToTheAttributesAndOutsideInTheResult) {
  geotandem::testing::ScratchDir dir;
  PluginRegistry registry;
  builtin::register_builtins(registry);
  synth::SeismicOptions o;
  o.shape = {44, 40, 52};
  o.seed = 5;
  o.snr = 3;
  const auto cube = synth::make_seismic(o);
  const volume::Geometry geometry = cube->geometry();
  const volume::Box bounds = geometry.bounds();
  std::vector<float> holes = cube->read(bounds), dead = holes;
  std::vector<bool> missing(holes.size(), false);
  for (std::int64_t i = 0; i < 44; ++i)
    for (std::int64_t j = 0; j < 40; ++j)
      for (std::int64_t k = 0; k < 52; ++k) {
        const auto n = static_cast<std::size_t>((i * 40 + j) * 52 + k);
        const bool corner = i < 12 && j < 15, spike = i == 30 && j == 20 && k == 25;
        if (!corner && !spike) continue;
        missing[n] = true;
        holes[n] = spike ? std::numeric_limits<float>::infinity() : std::numeric_limits<float>::quiet_NaN();
        dead[n] = 0.0f;
      }
  std::vector<float> nulls = holes;
  for (std::size_t n = 0; n < nulls.size(); ++n)
    if (missing[n] && std::isnan(nulls[n])) nulls[n] = -999.25f;
  volume::write_volume(volume::MemoryVolume(geometry, holes), dir.file("holes.raw"));
  volume::write_volume(volume::MemoryVolume(geometry, nulls), dir.file("nulls.raw"));
  volume::write_volume(volume::MemoryVolume(geometry, dead), dir.file("dead.raw"));

  using attributes::make_attribute;
  std::shared_ptr<const volume::Volume> zeros = volume::open_volume(dir.file("dead.raw"));
  auto chaos = make_attribute("chaos", {zeros}, {{"sigma_t_across", 2.0}});
  auto envelope = make_attribute("envelope", {zeros}, {{"half_length", std::int64_t{8}}});
  auto bright = make_attribute("normalise", {envelope}, {{"method", std::string("percentile")}});
  const auto facies = make_attribute("product", {chaos, bright});
  const std::vector<float> want = facies->read(bounds);

  const Recipe recipe = parse_recipe(facies_recipe(dir.file("holes.raw"), "fill", "facies"), "holes.yaml", registry);
  // The description says so: a store extracted when the attributes saw the fill's lowest float has
  // another fingerprint and is not reused.
  EXPECT_EQ(describe_chain(recipe, registry).input.value("missing", ""), "dead samples");
  const ChainVolumes chain = open_chain(describe_chain(recipe, registry), registry);
  std::size_t outside = 0, compared = 0;
  for (const volume::Box& box : slab_boxes(geometry.shape, 16, 5)) {
    const std::vector<float> got = chain.result->read(box);
    std::size_t m = 0;
    for (std::int64_t i = box.lo[0]; i < box.hi[0]; ++i)
      for (std::int64_t j = box.lo[1]; j < box.hi[1]; ++j)
        for (std::int64_t k = box.lo[2]; k < box.hi[2]; ++k, ++m) {
          const auto n = static_cast<std::size_t>((i * 40 + j) * 52 + k);
          if (missing[n]) {
            ASSERT_EQ(got[m], std::numeric_limits<float>::lowest()) << i << ", " << j << ", " << k;
            ++outside;
          } else {
            ASSERT_EQ(0, std::memcmp(&got[m], &want[n], sizeof(float)))
                << i << ", " << j << ", " << k << ": " << got[m] << " against " << want[n];
            ++compared;
          }
        }
  }
  EXPECT_GE(outside, 12u * 15u * 52u);
  EXPECT_GT(compared, outside);

  // The same traces holding a null value that input.no_data names: the same result, bit for bit.
  const Recipe nulled = parse_recipe(facies_recipe(dir.file("nulls.raw"), "fill", "facies", ", no_data: -999.25"),
                                     "nulls.yaml", registry);
  const ChainVolumes with_nulls = open_chain(describe_chain(nulled, registry), registry);
  for (const volume::Box& box : slab_boxes(geometry.shape, 16, 5)) {
    const std::vector<float> a = chain.result->read(box), b = with_nulls.result->read(box);
    ASSERT_EQ(0, std::memcmp(a.data(), b.data(), a.size() * sizeof(float))) << box.to_string();
  }

  // Read by the extraction directly, a missing sample is the lowest float, the others as in the file.
  const Recipe direct = parse_recipe(facies_recipe(dir.file("holes.raw"), "fill", "input"), "direct.yaml", registry);
  EXPECT_FALSE(describe_chain(direct, registry).input.contains("missing"));
  const std::vector<float> input = open_chain(describe_chain(direct, registry), registry).result->read(bounds);
  for (std::size_t n = 0; n < input.size(); ++n)
    ASSERT_EQ(input[n], missing[n] ? std::numeric_limits<float>::lowest() : holes[n]) << n;

  // Without the fill, the first missing sample stops the read, naming the file.
  const Recipe strict = parse_recipe(facies_recipe(dir.file("holes.raw"), "error", "facies"), "strict.yaml", registry);
  EXPECT_FALSE(describe_chain(strict, registry).input.contains("missing"));
  const ChainVolumes stopped = open_chain(describe_chain(strict, registry), registry);
  try {
    stopped.result->read(volume::Box{{0, 0, 0}, {8, 8, 52}});
    FAIL() << "a NaN sample was read without the fill";
  } catch (const DataError& e) {
    EXPECT_NE(std::string(e.what()).find("holes.raw"), std::string::npos) << e.what();
  }
}
