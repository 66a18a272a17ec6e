// Exports parsed back by independent readers written here: PLY header and binary body, OBJ and
// TSurf numbering, one file per component, failures. VTP has its own file (export_vtp_test.cpp).

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <sstream>

#include "export_fixture.hpp"
#include "geotandem/core/error.hpp"

namespace geotandem::store {
namespace {

using testing::ExportTest;
using testing::lines_of;
using testing::slurp;

struct PlyHeader {
  std::uint64_t vertices = 0, faces = 0, comments_with_keys = 0;
  std::string vertex_type;
  std::size_t length = 0;
};

PlyHeader parse_ply_header(const std::string& data) {
  PlyHeader h;
  auto end = data.find("end_header\n");
  EXPECT_NE(end, std::string::npos);
  h.length = end + std::strlen("end_header\n");
  auto lines = lines_of(data.substr(0, end));
  EXPECT_EQ(lines.at(0), "ply");
  EXPECT_EQ(lines.at(1), "format binary_little_endian 1.0");
  for (const auto& line : lines) {
    std::istringstream in(line);
    std::string word, what;
    in >> word;
    if (word == "element") {
      in >> what;
      (what == "vertex" ? h.vertices : h.faces) = std::stoull(line.substr(line.rfind(' ') + 1));
    } else if (word == "property" && h.faces == 0 && line.find("list") == std::string::npos) {
      in >> h.vertex_type;
    } else if (word == "comment" && line.find(" key ") != std::string::npos) {
      ++h.comments_with_keys;
    }
  }
  return h;
}

TEST_F(ExportTest, PlyHeaderSizeAndBodyAgreeWithTheStore) {
  auto path = scratch_.path() / "all.ply";
  auto summary = run(path, {ExportFormat::ply});
  EXPECT_EQ(summary.files, std::vector<std::filesystem::path>{path});
  EXPECT_EQ(summary.vertices, total_vertices());
  auto data = slurp(path);
  auto h = parse_ply_header(data);
  EXPECT_EQ(h.vertex_type, "double");
  EXPECT_EQ(h.vertices, total_vertices());
  EXPECT_EQ(h.faces, total_triangles());
  EXPECT_EQ(h.comments_with_keys, rows_.size());
  ASSERT_EQ(data.size(), h.length + 24 * h.vertices + 17 * h.faces);
  const char* p = data.data() + h.length;
  for (const auto& s : surfaces_)
    for (const auto& point : s.points) {
      mesh::Point read;
      std::memcpy(read.data(), p, 24);
      p += 24;
      EXPECT_EQ(read, point);
    }
  std::uint32_t base = 0;
  for (std::uint32_t body = 0; body < surfaces_.size(); ++body) {
    for (const auto& t : surfaces_[body].triangles) {
      EXPECT_EQ(*p, 3);
      std::int32_t index[3];
      std::uint32_t body_read = 0;
      std::memcpy(index, p + 1, 12);
      std::memcpy(&body_read, p + 13, 4);
      p += 17;
      for (int c = 0; c < 3; ++c)
        EXPECT_EQ(static_cast<std::uint32_t>(index[c]), base + t[c]);
      EXPECT_EQ(body_read, body);
    }
    base += static_cast<std::uint32_t>(surfaces_[body].points.size());
  }
}

TEST_F(ExportTest, PlyFloat32HalvesTheVertices) {
  auto path = scratch_.path() / "all32.ply";
  ExportOptions options{ExportFormat::ply};
  options.ply_float32 = true;
  run(path, options);
  auto data = slurp(path);
  auto h = parse_ply_header(data);
  EXPECT_EQ(h.vertex_type, "float");
  ASSERT_EQ(data.size(), h.length + 12 * h.vertices + 17 * h.faces);
  float first[3];
  std::memcpy(first, data.data() + h.length, 12);
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(first[c], surfaces_[0].points[0][c], 1.0); // float at 6e6 m: ~0.5 m
}

TEST_F(ExportTest, ObjCountsAndOneBasedIndices) {
  auto path = scratch_.path() / "all.obj";
  run(path, {ExportFormat::obj});
  std::vector<mesh::Point> points;
  std::vector<std::array<std::uint64_t, 3>> faces;
  std::vector<std::string> objects;
  for (const auto& line : lines_of(slurp(path))) {
    std::istringstream in(line);
    std::string tag;
    in >> tag;
    if (tag == "v") {
      mesh::Point p;
      in >> p[0] >> p[1] >> p[2];
      points.push_back(p);
    } else if (tag == "f") {
      std::array<std::uint64_t, 3> f;
      in >> f[0] >> f[1] >> f[2];
      faces.push_back(f);
    } else if (tag == "o") {
      std::string name;
      in >> name;
      objects.push_back(name);
    }
  }
  ASSERT_EQ(objects.size(), rows_.size());
  for (std::size_t i = 0; i < rows_.size(); ++i)
    EXPECT_EQ(objects[i], "geobody_" + std::to_string(rows_[i].key));
  ASSERT_EQ(points.size(), total_vertices());
  ASSERT_EQ(faces.size(), total_triangles());
  std::size_t v = 0, f = 0;
  std::uint64_t base = 1;
  for (const auto& s : surfaces_) {
    for (const auto& point : s.points)
      EXPECT_EQ(points[v++], point); // shortest round-trip text is exact
    for (const auto& t : s.triangles) {
      for (int c = 0; c < 3; ++c)
        EXPECT_EQ(faces[f][c], base + t[c]);
      ++f;
    }
    base += s.points.size();
  }
}

TEST_F(ExportTest, TsurfObjectsNumberTheirVerticesFromOne) {
  auto path = scratch_.path() / "all.ts";
  run(path, {ExportFormat::tsurf});
  auto lines = lines_of(slurp(path));
  std::size_t object = 0, i = 0;
  while (i < lines.size()) {
    ASSERT_LT(object, rows_.size());
    ASSERT_EQ(lines[i], "GOCAD TSurf 1") << "line " << i + 1;
    std::uint64_t next_id = 1, triangles = 0;
    bool header_named = false, tface = false;
    for (++i; i < lines.size() && lines[i] != "END"; ++i) {
      std::istringstream in(lines[i]);
      std::string tag;
      in >> tag;
      if (lines[i] == "name:geobody_" + std::to_string(rows_[object].key)) header_named = true;
      if (tag == "TFACE") tface = true;
      if (tag == "VRTX") {
        std::uint64_t id;
        mesh::Point p;
        in >> id >> p[0] >> p[1] >> p[2];
        EXPECT_EQ(id, next_id);
        EXPECT_EQ(p, surfaces_[object].points[id - 1]);
        ++next_id;
      }
      if (tag == "TRGL") {
        std::uint64_t a, b, c;
        in >> a >> b >> c;
        const auto& t = surfaces_[object].triangles[triangles++];
        EXPECT_EQ(a, t[0] + 1u);
        EXPECT_EQ(b, t[1] + 1u);
        EXPECT_EQ(c, t[2] + 1u);
        EXPECT_TRUE(a >= 1 && b >= 1 && c >= 1 && a < next_id && b < next_id && c < next_id);
      }
    }
    ASSERT_LT(i, lines.size()) << "object " << object << " has no END";
    EXPECT_TRUE(header_named && tface) << "object " << object;
    EXPECT_EQ(next_id - 1, surfaces_[object].points.size());
    EXPECT_EQ(triangles, surfaces_[object].triangles.size());
    ++object;
    ++i;
  }
  EXPECT_EQ(object, rows_.size());
}

TEST_F(ExportTest, PerComponentFilesAreNamedByKey) {
  for (auto format : {ExportFormat::ply, ExportFormat::obj, ExportFormat::vtp, ExportFormat::tsurf}) {
    auto dir = scratch_.path() / (std::string("each-") + file_extension(format));
    ExportOptions options{format};
    options.per_component = true;
    auto summary = run(dir, options);
    ASSERT_EQ(summary.files.size(), rows_.size());
    for (std::size_t i = 0; i < rows_.size(); ++i) {
      auto expected = dir / ("geobody_" + std::to_string(rows_[i].key) + "." + file_extension(format));
      EXPECT_EQ(summary.files[i], expected);
      ASSERT_TRUE(std::filesystem::is_regular_file(expected)) << expected;
      if (format == ExportFormat::ply) {
        auto h = parse_ply_header(slurp(expected));
        EXPECT_EQ(h.vertices, surfaces_[i].points.size());
        EXPECT_EQ(h.faces, surfaces_[i].triangles.size());
      }
    }
    std::size_t entries = 0;
    for ([[maybe_unused]] auto& e : std::filesystem::directory_iterator(dir))
      ++entries;
    EXPECT_EQ(entries, rows_.size()) << "no temporary file may remain";
  }
}

// The temporaries an export of `name` left in `dir` (".NAME.XXXXXX.tmp", geotandem::AtomicFile).
std::size_t temporaries(const std::filesystem::path& dir, const std::string& name) {
  std::size_t n = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    const auto file = e.path().filename().string();
    n += file.rfind("." + name + ".", 0) == 0 || file == name + ".part";
  }
  return n;
}

TEST_F(ExportTest, FailuresLeaveNoFileBehind) {
  NullProgress progress;
  EXPECT_THROW(export_components(*store_, {}, scratch_.path() / "none.ply", {}, progress, CancelToken{}),
               InvalidArgument);
  std::filesystem::create_directories(scratch_.path() / "adir");
  EXPECT_THROW(run(scratch_.path() / "adir", {ExportFormat::obj}), InvalidArgument);
  EXPECT_THROW(parse_export_format("stl"), InvalidArgument);
  EXPECT_EQ(parse_export_format("ts"), ExportFormat::tsurf);

  CancelToken cancel;
  cancel.cancel();
  EXPECT_THROW(export_components(*store_, rows_, scratch_.path() / "c.ply", {}, progress, cancel), Cancelled);
  EXPECT_FALSE(std::filesystem::exists(scratch_.path() / "c.ply"));
  EXPECT_EQ(temporaries(scratch_.path(), "c.ply"), 0u);

  // A damaged record fails the export with the key in the message.
  const auto& last = rows_.back();
  {
    std::fstream shard(shard_path(store_->directory(), "local"), std::ios::in | std::ios::out | std::ios::binary);
    shard.seekp(static_cast<std::streamoff>(last.location.offset + 50));
    char byte = 0;
    shard.seekg(static_cast<std::streamoff>(last.location.offset + 50));
    shard.read(&byte, 1);
    byte = static_cast<char>(~byte);
    shard.seekp(static_cast<std::streamoff>(last.location.offset + 50));
    shard.write(&byte, 1);
  }
  auto reopened = ComponentStore::open(store_->directory());
  try {
    export_components(reopened, rows_, scratch_.path() / "d.obj", {ExportFormat::obj}, progress, CancelToken{});
    ADD_FAILURE() << "a damaged record was exported";
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find("component " + std::to_string(last.key)), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(scratch_.path() / "d.obj"));
  EXPECT_EQ(temporaries(scratch_.path(), "d.obj"), 0u);
}

} // namespace
} // namespace geotandem::store
