// Writer of netCDF-4 and Zarr v2 cubes through GDAL's multidimensional API: one Float32 array
// [iline, xline, twt|depth] chunked by WriteOptions::chunk, 1-D coordinate variables for the three
// dimensions, and the geometry as geotandem_* attributes of the array (docs/formats-gdal.md).

#include <array>
#include <filesystem>

#include "formats.hpp"
#include "gdal_common.hpp"
#include "gdal_module.hpp"
#include "geotandem/core/error.hpp"

namespace geotandem::volume::detail {
namespace {

// The handles of one file being written. Declaration order matters: members are released in
// reverse, arrays and dimensions before the group and the group before the dataset, which is
// when the file is flushed.
struct Output {
  gdal::DatasetPtr dataset;
  std::shared_ptr<GDALGroup> root;
  std::array<std::shared_ptr<GDALDimension>, 3> dims;
  std::shared_ptr<GDALMDArray> array;

  void release_handles() {
    array.reset();
    dims = {};
    root.reset();
  }
};

[[noreturn]] void fail(const std::string& what, const gdal::ErrorCapture& errors, const std::string& path,
                       const std::string& block = {}) {
  throw IoError(what + errors.text(), {path, {}, {}, block, {}}, "check free disk space and write permission");
}

void write_number(GDALMDArray& array, const char* key, double value, const std::string& path,
                  const gdal::ErrorCapture& errors) {
  auto attribute = array.CreateAttribute(key, {}, GDALExtendedDataType::Create(GDT_Float64));
  if (!attribute || !attribute->Write(value)) fail(std::string("cannot write attribute ") + key, errors, path);
}

void write_text(GDALMDArray& array, const char* key, const std::string& value, const std::string& path,
                const gdal::ErrorCapture& errors) {
  auto attribute = array.CreateAttribute(key, {}, GDALExtendedDataType::CreateString());
  if (!attribute || !attribute->Write(value.c_str())) fail(std::string("cannot write attribute ") + key, errors, path);
}

// A 1-D Float64 coordinate variable named like its dimension, holding first + step * index.
void write_coordinates(GDALGroup& root, const std::shared_ptr<GDALDimension>& dim, double first, double step,
                       const char* unit, const std::string& path, const gdal::ErrorCapture& errors) {
  auto variable = root.CreateMDArray(dim->GetName(), {dim}, GDALExtendedDataType::Create(GDT_Float64));
  if (!variable) fail("cannot create the coordinate variable " + dim->GetName(), errors, path);
  std::vector<double> values(static_cast<std::size_t>(dim->GetSize()));
  for (std::size_t n = 0; n < values.size(); ++n)
    values[n] = first + step * static_cast<double>(n);
  const GUInt64 start = 0;
  const std::size_t count = values.size();
  // One Write() covering the whole variable, hence whole chunks (see the Zarr note in write_gdal_md).
  if (!variable->Write(&start, &count, nullptr, nullptr, GDALExtendedDataType::Create(GDT_Float64), values.data()))
    fail("cannot write the coordinate variable " + dim->GetName(), errors, path);
  if (unit) write_text(*variable, "units", unit, path, errors);
  // netCDF and Zarr link a variable named like its dimension on their own; the explicit link
  // serves the other drivers and is harmless here.
  dim->SetIndexingVariable(variable);
}

void create(Output& out, const Volume& volume, const std::string& path, Format format, const WriteOptions& options,
            const gdal::ErrorCapture& errors) {
  const Geometry& g = volume.geometry();
  const bool zarr = format == Format::zarr;
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName(zarr ? "Zarr" : "netCDF");
  if (!driver) fail(std::string("GDAL was built without the ") + (zarr ? "Zarr" : "netCDF") + " driver", errors, path);
  CPLStringList create_options;
  create_options.SetNameValue("FORMAT", zarr ? "ZARR_V2" : "NC4");
  out.dataset.reset(driver->CreateMultiDimensional(path.c_str(), nullptr, create_options.List()));
  if (!out.dataset) fail("cannot create the file", errors, path);
  out.root = out.dataset->GetRootGroup();
  if (!out.root) fail("cannot get the root group of the new file", errors, path);

  const bool depth = g.z_unit != SampleUnit::milliseconds;
  const std::array<const char*, 3> names{"iline", "xline", depth ? "depth" : "twt"};
  // Dimension types as GDAL's multidimensional model names them, for tools that look at them.
  const std::array<const char*, 3> types{"HORIZONTAL_Y", "HORIZONTAL_X", "VERTICAL"};
  for (std::size_t a = 0; a < 3; ++a) {
    out.dims[a] = out.root->CreateDimension(names[a], types[a], "", static_cast<GUInt64>(g.shape[a]));
    if (!out.dims[a]) fail(std::string("cannot create dimension ") + names[a], errors, path);
  }
  write_coordinates(*out.root, out.dims[0], g.inline0, g.inline_step, nullptr, path, errors);
  write_coordinates(*out.root, out.dims[1], g.crossline0, g.crossline_step, nullptr, path, errors);
  write_coordinates(*out.root, out.dims[2], g.z0, g.dz, to_string(g.z_unit), path, errors);

  // Always chunk explicitly: the drivers' defaults are poor for cubes (netCDF stores contiguous,
  // Zarr picks 1 x 256 x 256).
  std::string blocks;
  for (int a = 0; a < 3; ++a)
    blocks += (a ? "," : "") + std::to_string(std::min<std::int64_t>(options.chunk, g.shape[a]));
  CPLStringList array_options;
  array_options.SetNameValue("BLOCKSIZE", blocks.c_str());
  out.array = out.root->CreateMDArray(options.variable, {out.dims[0], out.dims[1], out.dims[2]},
                                      GDALExtendedDataType::Create(GDT_Float32), array_options.List());
  if (!out.array) fail("cannot create array " + options.variable, errors, path);
  for (const gdal::GeometryField& field : gdal::geometry_fields())
    write_number(*out.array, field.key, gdal::field_value(g, field), path, errors);
  write_text(*out.array, gdal::z_unit_key, to_string(g.z_unit), path, errors);
  // A WKT attribute rather than a CF grid_mapping: the dimensions are line numbers, not the
  // projected x and y a grid mapping would make of them.
  if (!g.crs.empty()) write_text(*out.array, gdal::crs_key, g.crs.wkt, path, errors);
}

} // namespace

void gdal::write_md(const Volume& volume, const std::string& path, Format format, const WriteOptions& options,
                    Progress& progress, const CancelToken& cancel) {
  if (format != Format::netcdf && format != Format::zarr)
    throw InvalidArgument(std::string("geotandem cannot write ") + format_name(format) + " through GDAL", {path},
                          "write netCDF-4 (.nc) or Zarr (.zarr)");
  if (options.variable.empty() || options.variable == "iline" || options.variable == "xline" ||
      options.variable == "twt" || options.variable == "depth")
    throw InvalidArgument("the array name '" + options.variable + "' is empty or taken by a dimension", {path},
                          "choose another variable name, such as 'amplitude'");
  gdal::register_drivers();
  gdal::ErrorCapture errors;
  Output out;
  try {
    create(out, volume, path, format, options, errors);
    // Zarr in GDAL 3.6 loses data when several Write() calls fill one chunk, so every Write()
    // covers whole chunks: the boxes are the chunks themselves (clipped at the far faces).
    const auto chunk = static_cast<std::int64_t>(options.chunk);
    gdal::stream_boxes(volume, {chunk, chunk, chunk}, std::string("writing ") + format_name(format), progress, cancel,
                       [&](const Box& box, std::span<const float> samples) {
                         std::array<GUInt64, 3> start{};
                         std::array<std::size_t, 3> count{};
                         for (int a = 0; a < 3; ++a) {
                           start[static_cast<std::size_t>(a)] = static_cast<GUInt64>(box.lo[a]);
                           count[static_cast<std::size_t>(a)] = static_cast<std::size_t>(box.size(a));
                         }
                         if (!out.array->Write(start.data(), count.data(), nullptr, nullptr,
                                               GDALExtendedDataType::Create(GDT_Float32), samples.data()))
                           fail("cannot write the samples", errors, path, "box " + box.to_string());
                       });
    out.release_handles();
    gdal::close_written(std::move(out.dataset), path);
  } catch (...) {
    // Leave no half-written cube behind: a later open would find a plausible but wrong file.
    out.release_handles();
    out.dataset.reset();
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
    throw;
  }
}

} // namespace geotandem::volume::detail
