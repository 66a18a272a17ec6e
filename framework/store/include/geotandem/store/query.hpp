#pragma once
// Filters over the store's index. Every filter runs on index columns only: no shard is read.

#include <array>
#include <cstdint>
#include <optional>
#include <string>

namespace geotandem::store {

// An axial azimuth interval in degrees clockwise from north. from <= to is the interval
// [from, to]; from > to wraps through north, e.g. 170:10 is [170, 180) together with [0, 10].
struct AzimuthRange {
  double from = 0.0;
  double to = 180.0;
  bool contains(double azimuth) const;
};

// An axis-aligned box in world coordinates (x east, y north, z down in the sample unit).
struct WorldBox {
  std::array<double, 3> min{};
  std::array<double, 3> max{};
  // True when the closed boxes [min, max] and [other_min, other_max] share a point.
  bool intersects(const std::array<double, 3>& other_min, const std::array<double, 3>& other_max) const;
};

// `selection`: the order in which the query's selection was saved (needs Query::selection).
enum class SortKey { key, volume, azimuth, selection };

struct Query {
  std::optional<double> min_volume, max_volume; // world volume units, inclusive
  std::optional<AzimuthRange> azimuth;
  std::optional<WorldBox> box; // components whose bounding box intersects this box
  std::optional<std::uint64_t> min_vertices, max_vertices;
  std::optional<std::uint64_t> min_triangles, max_triangles;
  bool closed_only = false;        // only bodies closed by themselves (not cut by the cube border, so no caps)
  std::string selection;           // only members of this named selection (empty: all components)
  std::optional<std::int64_t> run; // only components produced by this run
  SortKey sort = SortKey::key;
  bool descending = false; // ties are always broken by ascending key
  std::optional<std::uint64_t> limit;
};

// Parsers for command lines and recipes. Each throws InvalidArgument naming the text and the form
// it expects.
// "A:B" in degrees; values outside [0, 180] are reduced modulo 180 (axial data).
AzimuthRange parse_azimuth_range(const std::string& text);
// "x0,y0,z0,x1,y1,z1": two opposite corners in any order.
WorldBox parse_world_box(const std::string& text);
// "key", "volume", "azimuth" or "selection".
SortKey parse_sort_key(const std::string& text);
const char* to_string(SortKey key);

} // namespace geotandem::store
