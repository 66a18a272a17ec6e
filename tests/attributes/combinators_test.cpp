#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "fixtures.hpp"
#include "geotandem/attributes/chaos.hpp"
#include "geotandem/attributes/envelope.hpp"
#include "geotandem/attributes/normalise.hpp"
#include "geotandem/attributes/product.hpp"
#include "geotandem/core/error.hpp"

namespace geotandem::attributes {
namespace {

using testing::cube;
using testing::noise;

// A cube holding each of -1, 2, -3, ..., +-N once (signs alternate), in a scrambled order.
std::shared_ptr<volume::MemoryVolume> permutation_cube(const Index3& shape) {
  const std::int64_t count = shape[0] * shape[1] * shape[2];
  return cube(shape, [=](int i, int j, int k) {
    const std::int64_t n = (i * shape[1] + j) * shape[2] + k;
    const std::int64_t value = (n * 7919) % count + 1; // 7919 is prime and divides no cube size used here
    return value % 2 ? -static_cast<double>(value) : static_cast<double>(value);
  });
}

TEST(Normalise, FixedScaleDividesEverySample) {
  auto u = cube({6, 5, 12}, [](int i, int j, int k) { return noise(i, j, k); });
  Normalise n(u, {.method = ScaleMethod::fixed, .scale = 4.0});
  EXPECT_EQ(n.scale(), 4.0);
  const std::vector<float> in = u->samples(), out = n.read(u->geometry().bounds());
  for (std::size_t s = 0; s < in.size(); ++s)
    ASSERT_EQ(out[s], in[s] / 4.0f);
}

TEST(Normalise, PercentileOfTheWholeCubeIsTheNearestRank) {
  const Index3 shape{24, 20, 64};
  auto u = permutation_cube(shape);
  // One sampling box as large as the cube: the sample is every |value|, i.e. 1..N exactly once.
  for (double p : {50.0, 99.0, 100.0, 0.001}) {
    Normalise n(u, {.percentile = p, .sample_boxes = 1, .sample_edge = 256});
    ASSERT_EQ(n.sample_boxes().size(), 1u);
    EXPECT_EQ(n.sample_boxes().front(), u->geometry().bounds());
    EXPECT_EQ(n.scale(), std::ceil(p / 100.0 * 30720.0)) << "percentile " << p;
  }
}

TEST(Normalise, SampleGridIsRegularInsideAndDisjoint) {
  auto u = cube({40, 24, 64}, [](int, int, int) { return 1.0; });
  Normalise n(u, {.sample_boxes = 3, .sample_edge = 8});
  const std::vector<Box> boxes = n.sample_boxes();
  ASSERT_EQ(boxes.size(), 27u);
  for (std::size_t a = 0; a < boxes.size(); ++a) {
    EXPECT_TRUE(u->geometry().bounds().contains(boxes[a])) << boxes[a].to_string();
    EXPECT_EQ(boxes[a].shape(), (Index3{8, 8, 8}));
    for (std::size_t b = 0; b < a; ++b)
      EXPECT_TRUE(boxes[a].intersection(boxes[b]).empty());
  }
  // From face to face on each axis.
  EXPECT_EQ(boxes.front().lo, (Index3{0, 0, 0}));
  EXPECT_EQ(boxes.back().hi, (Index3{40, 24, 64}));
  // Fewer boxes than asked where they would not fit side by side; edges clipped to the cube.
  auto thin = cube({3, 20, 64}, [](int, int, int) { return 1.0; });
  const std::vector<Box> few = Normalise(thin, {.sample_boxes = 4, .sample_edge = 16}).sample_boxes();
  EXPECT_EQ(few.size(), 1u * 1u * 4u);
  EXPECT_EQ(few.front().shape(), (Index3{3, 16, 16}));
}

TEST(Normalise, ScaleIsTheSameWhicheverBoxIsReadFirstAndBoxesMatchTheWholeCube) {
  auto u = permutation_cube({24, 20, 64});
  Normalise first(u), second(u);
  first.read(Box{{20, 15, 60}, {24, 20, 64}});
  second.read(Box{{0, 0, 0}, {2, 2, 2}});
  EXPECT_EQ(first.scale(), second.scale());
  EXPECT_GT(first.scale(), 0.0);
  testing::expect_boxes_match_whole(Normalise(u));
}

TEST(Normalise, ZeroScaleIsADataError) {
  auto u = cube({8, 8, 16}, [](int, int, int) { return 0.0; });
  Normalise n(u);
  EXPECT_THROW(n.read(Box{{0, 0, 0}, {1, 1, 1}}), DataError);
}

TEST(Normalise, RejectsBadParametersNamingThem) {
  auto u = cube({4, 4, 16}, [](int, int, int k) { return k; });
  for (auto [options, text] :
       {std::pair{NormaliseOptions{.percentile = 0}, "'percentile'"},
        std::pair{NormaliseOptions{.percentile = 100.5}, "(0, 100]"},
        std::pair{NormaliseOptions{.scale = -1}, "'scale'"}, std::pair{NormaliseOptions{.sample_boxes = 0}, "[1, 16]"},
        std::pair{NormaliseOptions{.sample_edge = 0}, "'sample_edge'"}}) {
    try {
      Normalise n(u, options);
      FAIL() << text << " accepted";
    } catch (const InvalidArgument& e) {
      EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
    }
  }
}

TEST(Product, MultipliesSampleBySample) {
  auto a = cube({6, 5, 12}, [](int i, int j, int k) { return noise(i, j, k, 1); });
  auto b = cube({6, 5, 12}, [](int i, int j, int k) { return noise(i, j, k, 2); });
  const std::vector<float> p = Product(a, b).read(a->geometry().bounds());
  for (std::size_t s = 0; s < p.size(); ++s)
    ASSERT_EQ(p[s], a->samples()[s] * b->samples()[s]);
}

TEST(Product, RejectsInputsOfDifferentShapes) {
  auto a = cube({6, 5, 12}, [](int, int, int) { return 1.0; });
  auto b = cube({6, 5, 13}, [](int, int, int) { return 1.0; });
  try {
    Product p(a, b);
    FAIL() << "shapes differ";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("[0:6, 0:5, 0:13]"), std::string::npos) << e.what();
  }
  EXPECT_THROW(Product(a, nullptr), InvalidArgument);
}

TEST(Product, ChaoticHighAmplitudeChainIsBoxIndependent) {
  auto u = cube({24, 20, 64}, [](int i, int j, int k) {
    const double amplitude = (i > 8 && i < 16 && k > 20 && k < 44) ? 3.0 : 1.0;
    return amplitude * (std::cos(0.4 * k) + (amplitude > 1 ? noise(i, j, k) : 0.1 * noise(i, j, k)));
  });
  auto chaos = std::make_shared<Chaos>(u);
  auto envelope = std::make_shared<Normalise>(std::make_shared<Envelope>(u));
  Product product(chaos, envelope);
  EXPECT_EQ(product.halo(), (Index3{0, 0, 0}));
  EXPECT_EQ(product.total_halo(), (Index3{9, 9, 32}));
  testing::expect_boxes_match_whole(product);
  // The planted chaotic, bright body stands out: inside it the product is far above outside.
  const std::vector<float> inside = product.read(Box{{10, 5, 26}, {14, 15, 38}});
  const std::vector<float> outside = product.read(Box{{0, 0, 26}, {4, 20, 38}});
  const double in_mean = std::accumulate(inside.begin(), inside.end(), 0.0) / static_cast<double>(inside.size());
  const double out_mean = std::accumulate(outside.begin(), outside.end(), 0.0) / static_cast<double>(outside.size());
  EXPECT_GT(in_mean, 5.0 * out_mean);
  EXPECT_NE(product.source().find("chaos(formula=planarity"), std::string::npos) << product.source();
}

} // namespace
} // namespace geotandem::attributes
