// Bubble removal and azimuth sorting on a real store, against brute-force expectations.

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "geotandem/core/error.hpp"
#include "geotandem/store/local_sink.hpp"
#include "geotandem/workflow/component_steps.hpp"
#include "scratch.hpp"

using namespace geotandem;
using namespace geotandem::workflow;

namespace {

mesh::Component component(std::uint64_t key, double volume, double azimuth, bool closed, double area = 1.0,
                          std::uint64_t triangles = 4) {
  mesh::Component c;
  c.key = key;
  // The steps read only the index, but the record needs a surface: a tetrahedron (4 triangles) or
  // an octahedron (8); the store counts the triangles of the record.
  if (triangles == 8) {
    c.surface.points = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    c.surface.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  } else {
    c.surface.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    c.surface.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  }
  c.stats.vertex_count = c.surface.points.size();
  c.stats.triangle_count = triangles;
  c.stats.closed = closed;
  c.stats.cut_by_border = !closed;
  c.stats.volume = closed ? volume : 0.0;
  c.stats.area = area;
  c.stats.azimuth = azimuth;
  return c;
}

struct Fixture {
  explicit Fixture(const std::string& dir)
      : store(store::ComponentStore::create(dir, volume::Geometry{{32, 32, 32}})) {}
  void add(const std::vector<mesh::Component>& components) {
    store::LocalSink sink(store);
    for (const auto& c : components)
      sink.commit(c);
    sink.close();
  }
  store::ComponentStore store;
};

} // namespace

TEST(RemoveBubbles, ThresholdIsTheLargestOfTheRulesAndSelectionKeepsEveryComponent) {
  geotandem::testing::ScratchDir dir;
  Fixture f(dir.file("store"));
  std::vector<mesh::Component> cs;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> small(0.1, 5.0);
  for (std::uint64_t k = 1; k <= 300; ++k)
    cs.push_back(component(k, small(rng), 10, true));
  for (std::uint64_t k = 1000; k < 1005; ++k)
    cs.push_back(component(k, 1000.0 * double(k - 999), 40, true));
  f.add(cs);

  BubbleRemoval rules;
  rules.min_volume = 10;
  rules.min_volume_fraction = 0.3; // 0.3 * 5000 = 1500 > 10: the fraction decides
  auto r = remove_bubbles(f.store, rules);
  EXPECT_DOUBLE_EQ(r.threshold, 1500.0);
  EXPECT_EQ(r.before, 305u);
  EXPECT_EQ(r.kept, (std::vector<std::uint64_t>{1004, 1003, 1002, 1001})); // largest first; 1000 has 1000 < 1500
  auto sel = f.store.load_selection("kept");
  EXPECT_EQ(sel.keys.size(), 4u);
  EXPECT_EQ(f.store.size(), 305u) << "removal is non-destructive";

  // Brute-force oracle for a percentile rule.
  BubbleRemoval p;
  p.min_volume_percentile = 50;
  p.selection = "median";
  auto m = remove_bubbles(f.store, p);
  std::vector<double> v;
  for (const auto& c : cs)
    v.push_back(c.stats.volume);
  std::sort(v.begin(), v.end());
  double median = v[(v.size() + 1) / 2 - 1];
  EXPECT_DOUBLE_EQ(m.threshold, median);
  std::size_t expected =
      static_cast<std::size_t>(std::count_if(v.begin(), v.end(), [&](double x) { return x >= median; }));
  EXPECT_EQ(m.after, expected);
}

TEST(RemoveBubbles, CutComponentsAreJudgedByAreaAndMinTrianglesApplies) {
  geotandem::testing::ScratchDir dir;
  Fixture f(dir.file("store"));
  // Threshold volume 1000: the sphere of that volume has area (36 pi 1e6)^(1/3) ~ 483.6.
  f.add({component(1, 2000, 0, true, 1.0, 8), component(2, 0, 0, false, 600.0), component(3, 0, 0, false, 300.0),
         component(4, 5000, 0, true)});
  BubbleRemoval rules;
  rules.min_volume = 1000;
  auto r = remove_bubbles(f.store, rules);
  EXPECT_EQ(r.kept, (std::vector<std::uint64_t>{4, 1, 2}));
  rules.closed_only = true;
  rules.min_triangles = 5;
  EXPECT_EQ(remove_bubbles(f.store, rules).kept, (std::vector<std::uint64_t>{1}));
  rules.min_volume_fraction = 2.0;
  EXPECT_THROW(remove_bubbles(f.store, rules), InvalidArgument);
}

TEST(RemoveBubbles, AHollowBodysInnerSurfaceIsDroppedByAVolumeRuleOnly) {
  geotandem::testing::ScratchDir dir;
  Fixture f(dir.file("store"));
  // A hollow body: its outer surface (5000) and its inner one, whose enclosed volume is negative;
  // and a speck.
  f.add({component(1, 5000, 0, true), component(2, -800, 0, true), component(3, 2, 0, true)});
  BubbleRemoval rules;
  rules.closed_only = true; // no volume rule: nothing goes for its volume
  auto r = remove_bubbles(f.store, rules);
  EXPECT_EQ(r.kept, (std::vector<std::uint64_t>{1, 3, 2}));
  EXPECT_EQ(r.after, 3u);
  rules.min_volume_fraction = 0.1;
  r = remove_bubbles(f.store, rules);
  EXPECT_DOUBLE_EQ(r.threshold, 500.0);
  EXPECT_EQ(r.kept, (std::vector<std::uint64_t>{1}));
}

TEST(SortByAzimuth, HistogramRangeWithWrapAndAxialMean) {
  geotandem::testing::ScratchDir dir;
  Fixture f(dir.file("store"));
  f.add({component(1, 10, 175, true), component(2, 10, 5, true), component(3, 10, 3, true), component(4, 10, 90, true),
         component(5, 50, 178, true)});
  AzimuthSorting rules;
  rules.bins = 18;
  rules.azimuth_min = 170; // wraps past 180: [170, 180) and [0, 10]
  rules.azimuth_max = 10;
  auto r = sort_by_azimuth(f.store, rules);
  EXPECT_EQ(r.before, 5u);
  EXPECT_EQ(r.after, 4u);
  EXPECT_EQ(r.histogram[0], 2u);
  EXPECT_EQ(r.histogram[17], 2u);
  // Volume-weighted axial mean of 175, 5, 3, 178 (weights 10, 10, 10, 50): doubled angles sum to
  // (sin, cos) = (-2.443, 79.52), half their angle is 179.12; the resultant is nearly 1.
  double d = std::fmod(r.mean_azimuth - 179.12 + 360.0, 180.0);
  EXPECT_LT(std::min(d, 180.0 - d), 0.02) << r.mean_azimuth;
  EXPECT_GT(r.resultant_length, 0.98);
  // Ties in bin population: the lower bin first, then by volume.
  EXPECT_EQ(r.ranking, (std::vector<std::uint64_t>{2, 3, 5, 1}));
  EXPECT_EQ(f.store.load_selection("sorted").keys.size(), 4u);
}

TEST(SortByAzimuth, StartsFromTheNewestSelection) {
  geotandem::testing::ScratchDir dir;
  Fixture f(dir.file("store"));
  f.add({component(1, 10, 20, true), component(2, 1000, 30, true), component(3, 2000, 120, true)});
  BubbleRemoval big;
  big.min_volume = 100;
  remove_bubbles(f.store, big);
  auto r = sort_by_azimuth(f.store, AzimuthSorting{});
  EXPECT_EQ(r.before, 2u) << "the bubble-removal selection is the starting set";
  EXPECT_EQ(r.ranking.size(), 2u);
}
