#pragma once
// Helpers of the GDAL-backed format tests (gdal_test.cpp, gdal_foreign_test.cpp,
// gdal_coordinates_test.cpp, gdal_raster_test.cpp): a formula cube
// whose every sample is unique, files written through GDAL as other tools would, error capture.

#include <gdal_priv.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "geotandem/core/error.hpp"
#include "geotandem/core/progress.hpp"
#include "geotandem/volume/io.hpp"
#include "geotandem/volume/volume.hpp"

namespace gdal_fixtures {

namespace gv = geotandem::volume;

// Unique and exact in float32 for shapes below 100 on each axis, so a misplaced sample shows.
inline float value_at(std::int64_t i, std::int64_t j, std::int64_t k) {
  return static_cast<float>(i * 10000 + j * 100 + k) + 0.5f;
}

inline gv::Geometry test_geometry(gv::Index3 shape, gv::SampleUnit unit = gv::SampleUnit::milliseconds) {
  gv::Geometry g;
  g.shape = shape;
  g.inline0 = 1201;
  g.inline_step = 2;
  g.crossline0 = 3400.5;
  g.crossline_step = -1;
  g.z0 = 123.4;
  g.dz = 2.1;
  g.z_unit = unit;
  g.affine = {605123.25,  12.5 * std::cos(0.3), -25.0 * std::sin(0.3),
              6781234.75, 12.5 * std::sin(0.3), 25.0 * std::cos(0.3)};
  return g;
}

inline std::unique_ptr<gv::MemoryVolume> make_cube(const gv::Geometry& g) {
  std::vector<float> samples(g.sample_count());
  std::size_t n = 0;
  for (std::int64_t i = 0; i < g.shape[0]; ++i)
    for (std::int64_t j = 0; j < g.shape[1]; ++j)
      for (std::int64_t k = 0; k < g.shape[2]; ++k)
        samples[n++] = value_at(i, j, k);
  return std::make_unique<gv::MemoryVolume>(g, std::move(samples));
}

// Compares a box's samples with the formula; reports the first wrong index only.
inline void expect_formula(const std::vector<float>& samples, const gv::Box& box) {
  ASSERT_EQ(samples.size(), box.count());
  for (std::int64_t i = box.lo[0]; i < box.hi[0]; ++i)
    for (std::int64_t j = box.lo[1]; j < box.hi[1]; ++j)
      for (std::int64_t k = box.lo[2]; k < box.hi[2]; ++k)
        if (samples[box.offset({i, j, k})] != value_at(i, j, k)) {
          ADD_FAILURE() << "sample (" << i << ", " << j << ", " << k << ") of box " << box.to_string() << " is "
                        << samples[box.offset({i, j, k})] << ", expected " << value_at(i, j, k);
          return;
        }
}

inline std::string message_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const geotandem::FormatError& error) {
    return error.what();
  }
  ADD_FAILURE() << "no FormatError thrown";
  return {};
}

class RecordingProgress final : public geotandem::Progress {
public:
  void begin(const std::string&, std::uint64_t total, const std::string&) override { total_ = total; }
  void update(std::uint64_t done) override { last_ = done; }
  void end() override { ended_ = true; }
  std::uint64_t total_ = 0, last_ = 0;
  bool ended_ = false;
};

// Writes a multidimensional file with GDAL directly, as another tool would; `fill` creates the
// content and must let go of every handle it makes.
inline void write_foreign(const std::string& path, const char* driver_name,
                          const std::function<void(GDALGroup&)>& fill) {
  GDALAllRegister();
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName(driver_name);
  ASSERT_NE(driver, nullptr);
  const char* options[] = {"FORMAT=NC4", nullptr};
  GDALDataset* dataset = driver->CreateMultiDimensional(path.c_str(), nullptr, options);
  ASSERT_NE(dataset, nullptr);
  {
    auto root = dataset->GetRootGroup();
    fill(*root);
  }
  GDALClose(GDALDataset::ToHandle(dataset));
}

inline std::shared_ptr<GDALMDArray> add_array(GDALGroup& root, const std::string& name,
                                              const std::vector<std::shared_ptr<GDALDimension>>& dims,
                                              GDALDataType type) {
  auto array = root.CreateMDArray(name, dims, GDALExtendedDataType::Create(type));
  EXPECT_NE(array, nullptr);
  return array;
}

// Fills a 3-D array whose stored axes hold (inline, crossline, sample) as given by `axes`:
// stored dimension d is cube axis axes[d].
inline void fill_array(GDALMDArray& array, std::array<int, 3> axes) {
  const auto& dims = array.GetDimensions();
  std::array<std::size_t, 3> count{};
  for (std::size_t d = 0; d < 3; ++d)
    count[d] = static_cast<std::size_t>(dims[d]->GetSize());
  std::vector<double> values(count[0] * count[1] * count[2]);
  std::size_t n = 0;
  for (std::size_t a = 0; a < count[0]; ++a)
    for (std::size_t b = 0; b < count[1]; ++b)
      for (std::size_t c = 0; c < count[2]; ++c) {
        std::array<std::int64_t, 3> cube{};
        cube[static_cast<std::size_t>(axes[0])] = static_cast<std::int64_t>(a);
        cube[static_cast<std::size_t>(axes[1])] = static_cast<std::int64_t>(b);
        cube[static_cast<std::size_t>(axes[2])] = static_cast<std::int64_t>(c);
        values[n++] = value_at(cube[0], cube[1], cube[2]);
      }
  const GUInt64 start[3] = {0, 0, 0};
  ASSERT_TRUE(
      array.Write(start, count.data(), nullptr, nullptr, GDALExtendedDataType::Create(GDT_Float64), values.data()));
}

// Writes `values` as the coordinate variable of `dim`, stored as `type` (Float32 as some tools
// store them), with a `units` attribute unless `unit` is null.
inline void write_values(GDALGroup& root, const std::shared_ptr<GDALDimension>& dim, const std::vector<double>& values,
                         GDALDataType type, const char* unit) {
  auto variable = add_array(root, dim->GetName(), {dim}, type);
  const GUInt64 start = 0;
  const std::size_t count = values.size();
  ASSERT_TRUE(
      variable->Write(&start, &count, nullptr, nullptr, GDALExtendedDataType::Create(GDT_Float64), values.data()));
  if (unit) variable->CreateAttribute("units", {}, GDALExtendedDataType::CreateString())->Write(unit);
}

inline void write_coordinate(GDALGroup& root, const std::shared_ptr<GDALDimension>& dim, double first, double step,
                             const char* unit) {
  std::vector<double> values(static_cast<std::size_t>(dim->GetSize()));
  for (std::size_t n = 0; n < values.size(); ++n)
    values[n] = first + step * static_cast<double>(n);
  write_values(root, dim, values, GDT_Float64, unit);
}

// One axis of a netCDF file written by write_axes: its dimension, and its coordinate variable
// unless `values` is empty.
struct Axis {
  std::string name;
  std::size_t size = 0; // taken from values when they are given
  std::vector<double> values;
  GDALDataType type = GDT_Float64;
  const char* unit = nullptr;
};

// A netCDF file whose array "seismic" (Float32, the formula of value_at) spans the three axes.
inline void write_axes(const std::string& path, const std::array<Axis, 3>& axes) {
  write_foreign(path, "netCDF", [&](GDALGroup& root) {
    std::vector<std::shared_ptr<GDALDimension>> dims;
    for (const Axis& axis : axes) {
      dims.push_back(root.CreateDimension(axis.name, "", "", axis.values.empty() ? axis.size : axis.values.size()));
      if (!axis.values.empty()) write_values(root, dims.back(), axis.values, axis.type, axis.unit);
    }
    fill_array(*add_array(root, "seismic", dims, GDT_Float32), {0, 1, 2});
  });
}

} // namespace gdal_fixtures
