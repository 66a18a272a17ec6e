#pragma once
// The filter options `store ls` and `store export` share, and the store Query they make.

#include <CLI/CLI.hpp>

#include <cstdint>
#include <string>

#include "geotandem/store/query.hpp"

namespace geotandem::app {

// Filter options shared by ls and export. Options that were not given stay unset in the Query.
struct Filters {
  double min_volume = 0, max_volume = 0;
  std::uint64_t min_triangles = 0, max_triangles = 0, min_vertices = 0, max_vertices = 0, limit = 0;
  std::string azimuth, box, selection, sort = "key";
  bool closed = false, reverse = false;
  CLI::Option *min_volume_opt = nullptr, *max_volume_opt = nullptr, *min_triangles_opt = nullptr,
              *max_triangles_opt = nullptr, *min_vertices_opt = nullptr, *max_vertices_opt = nullptr,
              *limit_opt = nullptr;

  void add_to(CLI::App* cmd);
  store::Query query() const;
};

} // namespace geotandem::app
