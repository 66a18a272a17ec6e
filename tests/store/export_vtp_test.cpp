// The VTP export read back: XML structure and counts, every binary array decoded here (base64, its
// UInt64 byte count, little-endian values) and compared with the store, and, when python3 is
// there, decoded again by its XML parser, base64 and struct modules.

#include <gtest/gtest.h>

#include <bit>
#include <cstdlib>
#include <cstring>

#include "../../framework/store/src/export_writers.hpp"
#include "base64_decode.hpp"
#include "export_fixture.hpp"

namespace geotandem::store {
namespace {

using testing::ExportTest;
using testing::slurp;

// One <DataArray> as the file holds it.
struct VtpArray {
  std::string tag;                    // the opening tag
  std::string text;                   // between the tags, surrounding whitespace removed
  std::optional<std::string> decoded; // the bytes `text` encodes; nullopt when it is not base64
  std::uint64_t byte_count = 0;       // what the header announces
  std::string payload;                // the bytes after the header

  std::string attribute(const std::string& name) const {
    const auto at = tag.find(" " + name + "=\"");
    if (at == std::string::npos) return {};
    const auto begin = at + name.size() + 3;
    return tag.substr(begin, tag.find('"', begin) - begin);
  }

  template <class Value> std::vector<Value> values() const {
    std::vector<Value> v(payload.size() / sizeof(Value));
    std::memcpy(v.data(), payload.data(), v.size() * sizeof(Value));
    return v;
  }
};

VtpArray parse_array(const std::string& xml, std::size_t open) {
  VtpArray a;
  const auto tag_end = xml.find('>', open);
  a.tag = xml.substr(open, tag_end + 1 - open);
  const auto body_end = xml.find("</DataArray>", tag_end);
  const auto body = xml.substr(tag_end + 1, body_end - tag_end - 1);
  const auto first = body.find_first_not_of(" \n");
  if (first != std::string::npos) a.text = body.substr(first, body.find_last_not_of(" \n") + 1 - first);
  a.decoded = testing::decode_base64(a.text);
  if (a.decoded && a.decoded->size() >= 8) {
    std::memcpy(&a.byte_count, a.decoded->data(), 8);
    a.payload = a.decoded->substr(8);
  }
  return a;
}

// The DataArray called `name` inside the element `scope` (FieldData, CellData, Points, Polys).
VtpArray vtp_array(const std::string& xml, const std::string& scope, const std::string& name) {
  const auto from = xml.find("<" + scope);
  const auto to = xml.find("</" + scope + ">", from);
  EXPECT_NE(to, std::string::npos) << scope;
  const auto named = xml.find("Name=\"" + name + "\"", from);
  EXPECT_LT(named, to) << scope << " has no array " << name;
  return parse_array(xml, xml.rfind("<DataArray", named));
}

std::vector<VtpArray> every_array(const std::string& xml) {
  std::vector<VtpArray> arrays;
  for (auto at = xml.find("<DataArray"); at != std::string::npos; at = xml.find("<DataArray", at + 1))
    arrays.push_back(parse_array(xml, at));
  return arrays;
}

std::uint64_t bits(double value) {
  return std::bit_cast<std::uint64_t>(value);
}

TEST_F(ExportTest, VtpHasConsistentCountsAndPerBodyData) {
  auto path = scratch_.path() / "all.vtp";
  run(path, {ExportFormat::vtp});
  auto xml = slurp(path);
  const auto n_points = total_vertices(), n_polys = total_triangles();
  EXPECT_NE(xml.find("byte_order=\"LittleEndian\" header_type=\"UInt64\""), std::string::npos);
  EXPECT_EQ(xml.find("compressor"), std::string::npos);
  EXPECT_EQ(xml.find("format=\"ascii\""), std::string::npos);
  EXPECT_NE(xml.find("NumberOfPoints=\"" + std::to_string(n_points) + "\""), std::string::npos);
  EXPECT_NE(xml.find("NumberOfPolys=\"" + std::to_string(n_polys) + "\""), std::string::npos);

  auto points_array = vtp_array(xml, "Points", "Points");
  EXPECT_EQ(points_array.attribute("type"), "Float64");
  EXPECT_EQ(points_array.attribute("format"), "binary");
  auto points = points_array.values<double>();
  ASSERT_EQ(points.size(), 3 * n_points);
  std::size_t v = 0;
  for (const auto& s : surfaces_)
    for (const auto& point : s.points)
      for (double c : point)
        ASSERT_EQ(bits(points[v++]), bits(c)) << "point value " << v - 1;

  auto connectivity_array = vtp_array(xml, "Polys", "connectivity");
  auto offsets_array = vtp_array(xml, "Polys", "offsets");
  // Int32 while the indices fit (vtp_index_bits), as here.
  EXPECT_EQ(connectivity_array.attribute("type"), "Int32");
  EXPECT_EQ(offsets_array.attribute("type"), "Int32");
  auto connectivity = connectivity_array.values<std::int32_t>();
  auto offsets = offsets_array.values<std::int32_t>();
  ASSERT_EQ(connectivity.size(), 3 * n_polys);
  ASSERT_EQ(offsets.size(), n_polys);
  for (std::size_t t = 0; t < n_polys; ++t)
    ASSERT_EQ(offsets[t], static_cast<std::int32_t>(3 * (t + 1))) << "offset " << t;
  for (auto c : connectivity)
    ASSERT_TRUE(c >= 0 && static_cast<std::uint64_t>(c) < n_points) << c;

  auto cell_keys = vtp_array(xml, "CellData", "key").values<std::uint64_t>();
  auto cell_volumes = vtp_array(xml, "CellData", "volume").values<double>();
  auto cell_azimuths = vtp_array(xml, "CellData", "azimuth").values<double>();
  auto cell_bodies = vtp_array(xml, "CellData", "body");
  EXPECT_EQ(cell_bodies.attribute("type"), "UInt32");
  auto bodies = cell_bodies.values<std::uint32_t>();
  ASSERT_EQ(cell_keys.size(), n_polys);
  ASSERT_EQ(cell_volumes.size(), n_polys);
  ASSERT_EQ(cell_azimuths.size(), n_polys);
  ASSERT_EQ(bodies.size(), n_polys);
  // Each body's triangles, in order: its own indices and its key, volume and azimuth.
  std::size_t t = 0;
  std::int64_t base = 0;
  for (std::uint32_t body = 0; body < surfaces_.size(); ++body) {
    for (const auto& triangle : surfaces_[body].triangles) {
      for (int c = 0; c < 3; ++c)
        ASSERT_EQ(connectivity[3 * t + c], base + triangle[c]) << "triangle " << t;
      ASSERT_EQ(bodies[t], body) << "triangle " << t;
      ASSERT_EQ(cell_keys[t], rows_[body].key) << "triangle " << t;
      ASSERT_EQ(bits(cell_volumes[t]), bits(rows_[body].stats.volume)) << "triangle " << t;
      ASSERT_EQ(bits(cell_azimuths[t]), bits(rows_[body].stats.azimuth)) << "triangle " << t;
      ++t;
    }
    base += static_cast<std::int64_t>(surfaces_[body].points.size());
  }

  auto field_keys = vtp_array(xml, "FieldData", "key").values<std::uint64_t>();
  auto field_volumes = vtp_array(xml, "FieldData", "volume").values<double>();
  auto field_azimuths = vtp_array(xml, "FieldData", "azimuth").values<double>();
  ASSERT_EQ(field_keys.size(), rows_.size());
  ASSERT_EQ(field_volumes.size(), rows_.size());
  ASSERT_EQ(field_azimuths.size(), rows_.size());
  for (std::size_t i = 0; i < rows_.size(); ++i) {
    EXPECT_EQ(field_keys[i], rows_[i].key);
    EXPECT_EQ(bits(field_volumes[i]), bits(rows_[i].stats.volume));
    EXPECT_EQ(bits(field_azimuths[i]), bits(rows_[i].stats.azimuth));
  }
#ifdef GEOTANDEM_PYTHON3
  // Independent readers: python's XML parser, and its base64 and struct modules for the arrays.
  auto script = scratch_.path() / "check_vtp.py";
  std::ofstream(script) << R"py(import base64, struct, sys, xml.etree.ElementTree as ET
root = ET.parse(sys.argv[1]).getroot()
keys = [int(k) for k in sys.argv[2].split(",")]
assert root.tag == "VTKFile" and root.get("type") == "PolyData", root.tag
assert root.get("byte_order") == "LittleEndian" and root.get("header_type") == "UInt64"
assert root.get("compressor") is None
codes = {"Float64": "d", "Int64": "q", "UInt64": "Q", "UInt32": "I", "Int32": "i"}
def values(path, name):
    for a in root.findall(path):
        if a.get("Name") == name:
            assert a.get("format") == "binary", name
            raw = base64.b64decode(a.text.strip(), validate=True)
            (count,) = struct.unpack_from("<Q", raw)
            assert count == len(raw) - 8, (name, count, len(raw) - 8)
            code = codes[a.get("type")]
            assert count % struct.calcsize(code) == 0, name
            return struct.unpack_from("<%d%s" % (count // struct.calcsize(code), code), raw, 8)
    raise SystemExit("no array " + name)
piece = "PolyData/Piece/"
npts = int(root.find(piece[:-1]).get("NumberOfPoints"))
npolys = int(root.find(piece[:-1]).get("NumberOfPolys"))
assert len(values(piece + "Points/DataArray", "Points")) == 3 * npts
conn = values(piece + "Polys/DataArray", "connectivity")
assert len(conn) == 3 * npolys and all(0 <= c < npts for c in conn)
offsets = values(piece + "Polys/DataArray", "offsets")
assert len(offsets) == npolys and offsets[-1] == 3 * npolys
assert list(offsets) == list(range(3, 3 * npolys + 1, 3))
cells = {name: values(piece + "CellData/DataArray", name) for name in ("key", "volume", "azimuth", "body")}
for name, column in cells.items():
    assert len(column) == npolys, name
assert list(values("PolyData/FieldData/DataArray", "key")) == keys, keys
assert sorted(set(cells["body"])) == list(range(len(keys)))
assert all(k == keys[b] for k, b in zip(cells["key"], cells["body"]))
azimuths = values("PolyData/FieldData/DataArray", "azimuth")
assert all(a == azimuths[b] for a, b in zip(cells["azimuth"], cells["body"]))
assert len(values("PolyData/FieldData/DataArray", "volume")) == len(keys)
print("ok")
)py";
  std::string keys;
  for (const auto& row : rows_)
    keys += (keys.empty() ? "" : ",") + std::to_string(row.key);
  auto command = std::string(GEOTANDEM_PYTHON3) + " " + script.string() + " " + path.string() + " " + keys;
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
#endif
}

// A reader trusts each array's header: it must count exactly the bytes that follow, in one file of
// every body and in files of one body each (whose field arrays hold a single value).
TEST_F(ExportTest, VtpEveryHeaderCountsTheBytesThatFollowIt) {
  std::vector<std::filesystem::path> files{scratch_.path() / "all.vtp"};
  run(files[0], {ExportFormat::vtp});
  ExportOptions each{ExportFormat::vtp};
  each.per_component = true;
  auto summary = run(scratch_.path() / "each", each);
  files.insert(files.end(), summary.files.begin(), summary.files.end());
  for (const auto& file : files) {
    auto arrays = every_array(slurp(file));
    EXPECT_EQ(arrays.size(), 10u) << file; // 3 field, 4 cell, points, connectivity, offsets
    for (const auto& a : arrays) {
      SCOPED_TRACE(file.string() + ": " + a.tag);
      EXPECT_EQ(a.attribute("format"), "binary");
      ASSERT_TRUE(a.decoded) << "not one unbroken base64 text";
      ASSERT_GE(a.decoded->size(), 8u);
      EXPECT_EQ(a.byte_count, a.payload.size());
      const std::string type = a.attribute("type");
      const std::size_t value_size = type == "UInt32" || type == "Int32" ? 4 : 8;
      EXPECT_EQ(a.payload.size() % value_size, 0u);
      EXPECT_GT(a.payload.size(), 0u);
    }
  }
}

// Connectivity and offsets are Int32 up to the largest point index and offset an Int32 holds, and
// Int64 beyond (a store of more than 2^31 points or 715,827,882 triangles, too large to write here).
TEST(VtpIndexBits, Int32WhileEveryIndexAndOffsetFits) {
  constexpr std::uint64_t int32_max = 2147483647;
  EXPECT_EQ(detail::vtp_index_bits(0, 0), 32);
  EXPECT_EQ(detail::vtp_index_bits(int32_max, int32_max / 3), 32);
  EXPECT_EQ(detail::vtp_index_bits(int32_max + 1, 1), 64);
  EXPECT_EQ(detail::vtp_index_bits(1000, int32_max / 3 + 1), 64); // the last offset, 3 x polys, would not fit
}

} // namespace
} // namespace geotandem::store
