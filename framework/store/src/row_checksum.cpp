#include "row_checksum.hpp"

#include <xxhash.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <vector>

namespace geotandem::store::detail {
namespace {

static_assert(std::endian::native == std::endian::little, "row checksums hash little-endian bytes");

class RowBytes {
public:
  void integer(std::uint64_t v) { append(&v, sizeof v); }
  // As SQLite gives the value back: -0.0 comes back as 0.0 (a REAL that holds an integer is stored
  // as one), NaN as NULL, which reads 0.0.
  void real(double v) {
    if (v == 0.0 || std::isnan(v)) v = 0.0;
    append(&v, sizeof v);
  }
  void byte(std::uint8_t v) { append(&v, 1); }
  void text(const std::string& s) {
    integer(s.size());
    append(s.data(), s.size());
  }
  std::uint64_t hash() const { return XXH64(bytes_.data(), bytes_.size(), 0); }

private:
  void append(const void* data, std::size_t size) {
    const auto* p = static_cast<const unsigned char*>(data);
    bytes_.insert(bytes_.end(), p, p + size);
  }
  std::vector<unsigned char> bytes_;
};

} // namespace

std::uint64_t row_checksum(std::uint64_t key, const RecordLocation& l, const mesh::ComponentStats& st,
                           const std::optional<std::int64_t>& run, bool samples) {
  RowBytes b;
  b.integer(key);
  b.text(l.shard);
  b.integer(l.offset);
  b.integer(l.length);
  b.integer(l.checksum);
  b.integer(l.vertex_count);
  b.integer(l.triangle_count);
  b.real(st.volume);
  b.real(st.area);
  for (double v : st.centroid)
    b.real(v);
  for (double v : st.box_min)
    b.real(v);
  for (double v : st.box_max)
    b.real(v);
  for (double v : st.obb_center)
    b.real(v);
  for (const auto& axis : st.obb_axes)
    for (double v : axis)
      b.real(v);
  for (double v : st.obb_half_extents)
    b.real(v);
  b.real(st.azimuth);
  b.real(st.dip);
  b.real(st.elongation);
  b.byte(st.closed ? 1 : 0);
  b.byte(st.cut_by_border ? 1 : 0);
  b.byte(run ? 1 : 0);
  if (run) b.integer(static_cast<std::uint64_t>(*run));
  b.text(mesh::cut_faces_text(st.cut_faces));
  b.real(st.cap_area);
  // Rows with a samples column value (issue 54) checksum it too; rows from before keep theirs.
  if (samples) b.integer(static_cast<std::uint64_t>(st.samples));
  return b.hash();
}

} // namespace geotandem::store::detail
