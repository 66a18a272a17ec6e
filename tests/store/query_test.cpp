// Index queries against a brute-force filter over every row, and the filter parsers.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <random>

#include "fixtures.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/store/local_sink.hpp"
#include "geotandem/store/store.hpp"
#include "scratch.hpp"
#include "test_paths.hpp"

namespace geotandem::store {
namespace {

using geotandem::testing::ScratchDir;
using testing::make_component;
using testing::test_geometry;

// The keys of the selection "subset", in their saved order.
const std::vector<std::uint64_t>& subset() {
  static const std::vector<std::uint64_t> keys = [] {
    std::vector<std::uint64_t> k;
    for (std::uint64_t key = 1; key <= 240; key += 2)
      k.push_back(key);
    std::shuffle(k.begin(), k.end(), std::mt19937_64(5));
    return k;
  }();
  return keys;
}

// The oracle: the filter written out plainly over the full row list.
bool matches(const ComponentRow& r, const Query& q) {
  const auto& s = r.stats;
  if (q.min_volume && s.volume < *q.min_volume) return false;
  if (q.max_volume && s.volume > *q.max_volume) return false;
  if (q.azimuth) {
    const double a = s.azimuth, from = q.azimuth->from, to = q.azimuth->to;
    bool inside = from <= to ? (a >= from && a <= to) : (a >= from || a <= to);
    if (!inside) return false;
  }
  if (q.box) {
    for (int d = 0; d < 3; ++d)
      if (s.box_max[d] < q.box->min[d] || s.box_min[d] > q.box->max[d]) return false;
  }
  if (q.min_vertices && s.vertex_count < *q.min_vertices) return false;
  if (q.max_vertices && s.vertex_count > *q.max_vertices) return false;
  if (q.min_triangles && s.triangle_count < *q.min_triangles) return false;
  if (q.max_triangles && s.triangle_count > *q.max_triangles) return false;
  if (q.closed_only && !s.closed) return false;
  if (!q.selection.empty() && std::find(subset().begin(), subset().end(), r.key) == subset().end()) return false;
  return true;
}

std::vector<std::uint64_t> brute_force(std::vector<ComponentRow> all, const Query& q) {
  std::vector<ComponentRow> kept;
  for (auto& r : all)
    if (matches(r, q)) kept.push_back(r);
  auto value = [&](const ComponentRow& r) {
    return q.sort == SortKey::volume ? r.stats.volume : q.sort == SortKey::azimuth ? r.stats.azimuth : 0.0;
  };
  std::stable_sort(kept.begin(), kept.end(), [&](const ComponentRow& a, const ComponentRow& b) {
    if (q.sort == SortKey::key) return q.descending ? a.key > b.key : a.key < b.key;
    if (q.sort == SortKey::selection) {
      auto pa = std::find(subset().begin(), subset().end(), a.key);
      auto pb = std::find(subset().begin(), subset().end(), b.key);
      return q.descending ? pa > pb : pa < pb;
    }
    if (value(a) != value(b)) return q.descending ? value(a) > value(b) : value(a) < value(b);
    return a.key < b.key;
  });
  if (q.limit && kept.size() > *q.limit) kept.resize(*q.limit);
  std::vector<std::uint64_t> keys;
  for (auto& r : kept)
    keys.push_back(r.key);
  return keys;
}

std::vector<std::uint64_t> keys_of(const std::vector<ComponentRow>& rows) {
  std::vector<std::uint64_t> keys;
  for (auto& r : rows)
    keys.push_back(r.key);
  return keys;
}

class QueryTest : public ::testing::Test {
protected:
  // One store for the suite, in a directory of its own: CTest may run the cases as parallel processes.
  static void SetUpTestSuite() {
    dir_ = std::filesystem::path(test_paths::scratch()) / ("QueryTest-" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir_);
    store_ = new ComponentStore(ComponentStore::create(dir_, test_geometry()));
    LocalSink sink(*store_, {"local", std::nullopt, 64});
    for (std::uint64_t key = 1; key <= 240; ++key)
      sink.commit(make_component(key, test_geometry(), 1));
    sink.close();
    store_->save_selection("subset", subset(), R"({"every": "odd key"})");
  }
  static void TearDownTestSuite() {
    delete store_;
    std::filesystem::remove_all(dir_);
  }
  static std::filesystem::path dir_;
  static ComponentStore* store_;
};
std::filesystem::path QueryTest::dir_;
ComponentStore* QueryTest::store_ = nullptr;

TEST_F(QueryTest, RandomFilterCombinationsAgreeWithBruteForce) {
  const auto all = store_->query();
  ASSERT_EQ(all.size(), 240u);
  std::vector<double> volumes, azimuths;
  for (auto& r : all) {
    volumes.push_back(r.stats.volume);
    azimuths.push_back(r.stats.azimuth);
  }
  std::mt19937_64 rng(2024);
  auto pick = [&](const std::vector<double>& values) { return values[rng() % values.size()]; };
  const auto& first = all.front().stats;
  std::array<double, 3> lo = first.box_min, hi = first.box_max;
  for (auto& r : all)
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], r.stats.box_min[d]);
      hi[d] = std::max(hi[d], r.stats.box_max[d]);
    }
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::size_t non_trivial = 0;
  for (int round = 0; round < 300; ++round) {
    Query q;
    // Bounds are often existing values, so that inclusive ends are tested.
    if (rng() % 3 == 0) q.min_volume = pick(volumes);
    if (rng() % 3 == 0) q.max_volume = std::max(q.min_volume.value_or(0.0), pick(volumes));
    if (rng() % 2 == 0) q.azimuth = AzimuthRange{pick(azimuths), pick(azimuths)}; // half of them wrap
    if (rng() % 3 == 0) {
      WorldBox box;
      for (int d = 0; d < 3; ++d) {
        double a = lo[d] + (hi[d] - lo[d]) * unit(rng), b = lo[d] + (hi[d] - lo[d]) * unit(rng);
        box.min[d] = std::min(a, b);
        box.max[d] = std::max(a, b);
      }
      q.box = box;
    }
    if (rng() % 4 == 0) q.min_vertices = 42;
    if (rng() % 4 == 0) q.max_triangles = 20;
    if (rng() % 4 == 0) q.min_triangles = 80;
    if (q.min_triangles && q.max_triangles) q.max_triangles.reset();
    if (rng() % 4 == 0) q.closed_only = true;
    if (rng() % 3 == 0) q.selection = "subset";
    q.sort = static_cast<SortKey>(rng() % (q.selection.empty() ? 3 : 4));
    q.descending = rng() % 2 == 0;
    if (rng() % 3 == 0) q.limit = rng() % 20;
    auto expected = brute_force(all, q);
    EXPECT_EQ(keys_of(store_->query(q)), expected) << "round " << round;
    auto unlimited = q;
    unlimited.limit.reset();
    EXPECT_EQ(store_->count(q), brute_force(all, unlimited).size()) << "round " << round;
    if (!expected.empty() && expected.size() < all.size()) ++non_trivial;
  }
  EXPECT_GT(non_trivial, 100u); // the filters really split the rows
}

TEST_F(QueryTest, AzimuthRangeWrapsThroughNorth) {
  const auto all = store_->query();
  Query q;
  q.azimuth = parse_azimuth_range("170:10");
  auto rows = store_->query(q);
  ASSERT_FALSE(rows.empty());
  std::size_t expected = 0;
  for (auto& r : all)
    expected += (r.stats.azimuth >= 170.0 || r.stats.azimuth <= 10.0);
  EXPECT_EQ(rows.size(), expected);
  for (auto& r : rows)
    EXPECT_TRUE(r.stats.azimuth >= 170.0 || r.stats.azimuth <= 10.0) << r.stats.azimuth;
  // The complement plus the range covers everything once (ends belong to both).
  Query rest;
  rest.azimuth = AzimuthRange{10.0, 170.0};
  std::size_t on_ends = 0;
  for (auto& r : all)
    on_ends += (r.stats.azimuth == 10.0 || r.stats.azimuth == 170.0);
  EXPECT_EQ(store_->count(q) + store_->count(rest), all.size() + on_ends);
}

TEST_F(QueryTest, SortByVolumeDescendingGivesTheLargestFirst) {
  Query q;
  q.sort = SortKey::volume;
  q.descending = true;
  q.limit = 5;
  auto rows = store_->query(q);
  ASSERT_EQ(rows.size(), 5u);
  double largest = 0.0;
  for (auto& r : store_->query())
    largest = std::max(largest, r.stats.volume);
  EXPECT_EQ(rows[0].stats.volume, largest);
  for (std::size_t i = 1; i < rows.size(); ++i)
    EXPECT_GE(rows[i - 1].stats.volume, rows[i].stats.volume);
}

TEST_F(QueryTest, InconsistentBoundsAreRefused) {
  Query q;
  q.min_volume = 10.0;
  q.max_volume = 1.0;
  EXPECT_THROW(store_->query(q), InvalidArgument);
  Query t;
  t.min_triangles = 100;
  t.max_triangles = 10;
  EXPECT_THROW(store_->count(t), InvalidArgument);
}

TEST(QueryParse, AzimuthRanges) {
  auto r = parse_azimuth_range("30:60");
  EXPECT_EQ(r.from, 30.0);
  EXPECT_EQ(r.to, 60.0);
  EXPECT_TRUE(r.contains(45.0));
  EXPECT_FALSE(r.contains(61.0));
  auto wrap = parse_azimuth_range("170:10");
  EXPECT_TRUE(wrap.contains(175.0));
  EXPECT_TRUE(wrap.contains(5.0));
  EXPECT_FALSE(wrap.contains(90.0));
  auto reduced = parse_azimuth_range("-10:190");
  EXPECT_EQ(reduced.from, 170.0);
  EXPECT_EQ(reduced.to, 10.0);
  auto whole = parse_azimuth_range("0:180");
  EXPECT_TRUE(whole.contains(0.0) && whole.contains(179.9));
  EXPECT_EQ(parse_azimuth_range(" 12.5 : 14 ").from, 12.5);
  for (const char* bad : {"", "30", "30:", ":40", "a:b", "1:2:3", "30-60", "nan:10", "1e999:3"})
    EXPECT_THROW(parse_azimuth_range(bad), InvalidArgument) << bad;
}

TEST(QueryParse, BoxesAndSortKeys) {
  auto box = parse_world_box("10,20,30,0,5,100");
  EXPECT_EQ(box.min, (std::array<double, 3>{0, 5, 30}));
  EXPECT_EQ(box.max, (std::array<double, 3>{10, 20, 100}));
  EXPECT_TRUE(box.intersects({10, 20, 100}, {11, 21, 101})); // touching counts
  EXPECT_FALSE(box.intersects({10.5, 0, 0}, {11, 1, 1}));
  for (const char* bad : {"", "1,2,3,4,5", "1,2,3,4,5,6,7", "1,2,x,4,5,6", "1;2;3;4;5;6"})
    EXPECT_THROW(parse_world_box(bad), InvalidArgument) << bad;
  EXPECT_EQ(parse_sort_key("volume"), SortKey::volume);
  EXPECT_EQ(parse_sort_key("azimuth"), SortKey::azimuth);
  EXPECT_EQ(parse_sort_key("key"), SortKey::key);
  EXPECT_THROW(parse_sort_key("size"), InvalidArgument);
  EXPECT_STREQ(to_string(SortKey::azimuth), "azimuth");
}

} // namespace
} // namespace geotandem::store
