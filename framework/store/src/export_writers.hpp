#pragma once
// The format writers behind export_components. Each writes the components of a SurfaceSource, in
// its order, to one stream.

#include <charconv>
#include <functional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "geotandem/store/export.hpp"

namespace geotandem::store::detail {

// Hands out the world surfaces of a list of rows. Formats that write all points before all
// triangles (PLY, VTP) visit each component twice: surfaces are kept after the first read while
// they fit in `cache_budget` bytes, and read again otherwise, so memory stays bounded.
class SurfaceSource {
public:
  SurfaceSource(const ComponentStore& store, std::vector<const ComponentRow*> rows, std::function<void()> on_first_read,
                std::uint64_t cache_budget = 256ull << 20, bool caps = true);
  std::size_t size() const { return rows_.size(); }
  // Counts of row i as surface(i) hands it out (from the index, or from the surface when the caps
  // are left out).
  std::uint64_t vertex_count(std::size_t i);
  std::uint64_t triangle_count(std::size_t i);
  const ComponentRow& row(std::size_t i) const { return *rows_[i]; }
  // The surface of row i; the reference stays valid until the next call.
  const mesh::SurfaceMesh& surface(std::size_t i);
  const ComponentStore& store() const { return store_; }

private:
  const ComponentStore& store_;
  std::vector<const ComponentRow*> rows_;
  std::function<void()> on_first_read_;
  std::vector<mesh::SurfaceMesh> cache_;
  std::vector<bool> seen_;
  bool cache_all_ = false;
  bool caps_ = true;
  mesh::SurfaceMesh scratch_;
};

void write_ply(SurfaceSource& source, std::ostream& out, const ExportOptions& options);
void write_obj(SurfaceSource& source, std::ostream& out, const ExportOptions& options);
void write_vtp(SurfaceSource& source, std::ostream& out, const ExportOptions& options);
// The width of the VTP's connectivity and offsets: Int32 while every point index and offset fits
// (half the bytes of Int64; VTK readers take either), else Int64.
int vtp_index_bits(std::uint64_t points, std::uint64_t polys);
void write_tsurf(SurfaceSource& source, std::ostream& out, const ExportOptions& options);
// The GeoPackage is written by GDAL to a file, not a stream: written under a unique temporary name
// beside `path` and renamed over it when complete (export_gpkg.cpp). `tick` after each component.
void write_gpkg(const ComponentStore& store, const std::vector<const ComponentRow*>& rows,
                const std::filesystem::path& path, const ExportOptions& options, const std::function<void()>& tick);

// Shortest text that reads back to the same double (std::to_chars), for the text formats.
inline void put_number(std::ostream& out, double value) {
  char text[32];
  auto result = std::to_chars(text, text + sizeof text, value);
  out.write(text, result.ptr - text);
}

// The text formats' lines, built in memory and handed to the stream in pieces of about 64 KiB:
// one stream call per piece instead of one per token. flush() hands over what is left.
class TextLines {
public:
  explicit TextLines(std::ostream& out) : out_(out) { buffer_.reserve(kPiece + 256); }
  TextLines& operator<<(std::string_view text) {
    buffer_.append(text);
    return *this;
  }
  TextLines& operator<<(char c) {
    buffer_.push_back(c);
    return *this;
  }
  // As put_number: the shortest text that reads back to the same value.
  TextLines& operator<<(double value) { return number(value); }
  TextLines& operator<<(std::uint64_t value) { return number(value); }
  // Ends a line, and hands the buffer to the stream once it is a piece long.
  void end_line() {
    buffer_.push_back('\n');
    if (buffer_.size() >= kPiece) flush();
  }
  void flush() {
    out_.write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
    buffer_.clear();
  }

private:
  static constexpr std::size_t kPiece = std::size_t{1} << 16;
  template <class Value> TextLines& number(Value value) {
    char text[32];
    auto result = std::to_chars(text, text + sizeof text, value);
    buffer_.append(text, result.ptr);
    return *this;
  }

  std::ostream& out_;
  std::string buffer_;
};

} // namespace geotandem::store::detail
