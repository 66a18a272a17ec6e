#pragma once
// The export tests' store: four components from formulas, and the surfaces they hold, to compare
// the exported files with.

#include <gtest/gtest.h>

#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "fixtures.hpp"
#include "geotandem/store/export.hpp"
#include "geotandem/store/local_sink.hpp"
#include "scratch.hpp"

namespace geotandem::store::testing {

inline std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

inline std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    lines.push_back(line);
  return lines;
}

class ExportTest : public ::testing::Test {
protected:
  void SetUp() override {
    store_.emplace(ComponentStore::create(scratch_.path() / "store", test_geometry()));
    LocalSink sink(*store_, {"local", std::nullopt, 8});
    for (std::uint64_t key : {5, 12, 31, 44})
      sink.commit(make_component(key, test_geometry(), 2));
    sink.close();
    rows_ = store_->query();
    for (const auto& row : rows_)
      surfaces_.push_back(store_->read(row));
  }

  ExportSummary run(const std::filesystem::path& out, ExportOptions options) {
    NullProgress progress;
    return export_components(*store_, rows_, out, options, progress, CancelToken{});
  }

  std::uint64_t total_vertices() const {
    std::uint64_t n = 0;
    for (auto& s : surfaces_)
      n += s.points.size();
    return n;
  }
  std::uint64_t total_triangles() const {
    std::uint64_t n = 0;
    for (auto& s : surfaces_)
      n += s.triangles.size();
    return n;
  }

  geotandem::testing::ScratchDir scratch_;
  std::optional<ComponentStore> store_;
  std::vector<ComponentRow> rows_;
  std::vector<mesh::SurfaceMesh> surfaces_;
};

} // namespace geotandem::store::testing
