// Writes a cube as a netCDF-4 file stored in whole inline slices, as a tool writing inline by
// inline along an unlimited first dimension leaves it (netCDF's default chunks are then one inline
// each): the layout that reads by blocks decode many times over (docs/formats-gdal.md, "Chunks").
// For bench/paper_cube.sh --netcdf-slices; not how geotandem writes (64^3 chunks).
//
//   bench_netcdf_slices IN OUT [deflate=1: zlib level, 0 for none]
//
// IN is any cube geotandem reads; it is read one inline at a time. OUT gets iline, xline and twt
// dimensions with coordinate variables (line numbers and the sample times or depths).
#include <gdal_priv.h>

#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench_args.hpp"
#include "geotandem/volume/io.hpp"

namespace {

using namespace geotandem;

void coordinate(GDALGroup& root, const std::shared_ptr<GDALDimension>& dim, double first, double step,
                const char* unit) {
  auto array = root.CreateMDArray(dim->GetName(), {dim}, GDALExtendedDataType::Create(GDT_Float64));
  if (!array) throw std::runtime_error("cannot create the coordinate variable " + dim->GetName());
  std::vector<double> values(static_cast<std::size_t>(dim->GetSize()));
  for (std::size_t i = 0; i < values.size(); ++i)
    values[i] = first + step * static_cast<double>(i);
  const GUInt64 start[1] = {0};
  const std::size_t count[1] = {values.size()};
  if (!array->Write(start, count, nullptr, nullptr, GDALExtendedDataType::Create(GDT_Float64), values.data()))
    throw std::runtime_error("cannot write the coordinate variable " + dim->GetName());
  if (unit) array->SetUnit(unit);
}

int bench_main(int argc, char** argv) {
  const bench::Args args(argc, argv, "bench_netcdf_slices IN OUT [deflate=1]");
  if (!args.has(2)) args.fail(2, "is missing: the output file");
  const std::string in = args.text(1, ""), out = args.text(2, "");
  const std::int64_t level = args.integer(3, 1, 0);
  const auto cube = volume::open_volume(in);
  const volume::Geometry& g = cube->geometry();
  const volume::Index3 n = g.shape;

  GDALAllRegister();
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("netCDF");
  if (!driver) throw std::runtime_error("GDAL has no netCDF driver");
  const char* dataset_options[] = {"FORMAT=NC4", nullptr};
  GDALDataset* dataset = driver->CreateMultiDimensional(out.c_str(), nullptr, dataset_options);
  if (!dataset) throw std::runtime_error("cannot create " + out);
  {
    auto root = dataset->GetRootGroup();
    auto il = root->CreateDimension("iline", "", "", static_cast<GUInt64>(n[0]));
    auto xl = root->CreateDimension("xline", "", "", static_cast<GUInt64>(n[1]));
    auto tw = root->CreateDimension("twt", "", "", static_cast<GUInt64>(n[2]));
    coordinate(*root, il, static_cast<double>(g.inline0), static_cast<double>(g.inline_step), nullptr);
    coordinate(*root, xl, static_cast<double>(g.crossline0), static_cast<double>(g.crossline_step), nullptr);
    coordinate(*root, tw, g.z0, g.dz, g.z_unit == volume::SampleUnit::milliseconds ? "ms" : "m");
    const std::string blocks = "BLOCKSIZE=1," + std::to_string(n[1]) + "," + std::to_string(n[2]);
    const std::string zlevel = "ZLEVEL=" + std::to_string(level);
    std::vector<const char*> options{blocks.c_str()};
    if (level > 0) {
      options.push_back("COMPRESS=DEFLATE");
      options.push_back(zlevel.c_str());
    }
    options.push_back(nullptr);
    auto array = root->CreateMDArray("amplitude", {il, xl, tw}, GDALExtendedDataType::Create(GDT_Float32),
                                     const_cast<char**>(options.data()));
    if (!array) throw std::runtime_error("cannot create the array of " + out);
    std::vector<float> slice(static_cast<std::size_t>(n[1] * n[2]));
    for (std::int64_t i = 0; i < n[0]; ++i) {
      cube->read(volume::Box{{i, 0, 0}, {i + 1, n[1], n[2]}}, slice);
      const GUInt64 start[3] = {static_cast<GUInt64>(i), 0, 0};
      const std::size_t count[3] = {1, static_cast<std::size_t>(n[1]), static_cast<std::size_t>(n[2])};
      if (!array->Write(start, count, nullptr, nullptr, GDALExtendedDataType::Create(GDT_Float32), slice.data()))
        throw std::runtime_error("cannot write inline " + std::to_string(i) + " of " + out);
    }
  }
  GDALClose(GDALDataset::ToHandle(dataset));
  std::printf("%s: %lld x %lld x %lld in chunks of 1 x %lld x %lld, deflate %lld\n", out.c_str(),
              static_cast<long long>(n[0]), static_cast<long long>(n[1]), static_cast<long long>(n[2]),
              static_cast<long long>(n[1]), static_cast<long long>(n[2]), static_cast<long long>(level));
  return 0;
}

} // namespace

int main(int argc, char** argv) {
  return geotandem::bench::guarded_main("bench_netcdf_slices", [&] { return bench_main(argc, argv); });
}
