#include "gdal_md_inspect.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <vector>

#include "gdal_common.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/core/params.hpp"

namespace geotandem::volume::detail::gdal {
namespace {

struct Found {
  std::string full_name;
  std::shared_ptr<GDALMDArray> array;
};

// Every array of `group` and its subgroups. Depth-limited: a cube is never buried deep, and a
// malformed file must not send us round a loop of links.
void collect(GDALGroup& group, std::vector<Found>& out, int depth) {
  for (const std::string& name : group.GetMDArrayNames())
    if (auto array = group.OpenMDArray(name)) out.push_back({array->GetFullName(), std::move(array)});
  if (depth >= 4) return;
  for (const std::string& name : group.GetGroupNames())
    if (auto child = group.OpenGroup(name)) collect(*child, out, depth + 1);
}

bool is_float(const GDALMDArray& array) {
  const GDALExtendedDataType& type = array.GetDataType();
  return type.GetClass() == GEDTC_NUMERIC &&
         (type.GetNumericDataType() == GDT_Float32 || type.GetNumericDataType() == GDT_Float64);
}

bool is_cube(const GDALMDArray& array) {
  return array.GetDimensionCount() == 3 && is_float(array);
}

std::string type_of(const GDALMDArray& array) {
  const GDALExtendedDataType& type = array.GetDataType();
  if (type.GetClass() == GEDTC_STRING) return "String";
  if (type.GetClass() == GEDTC_COMPOUND) return "Compound";
  return type_name(type.GetNumericDataType());
}

// "amplitude (Float32, 37x29x53)"
std::string describe(const Found& found) {
  std::string shape;
  for (const auto& dim : found.array->GetDimensions())
    shape += (shape.empty() ? "" : "x") + std::to_string(dim->GetSize());
  return found.full_name + " (" + type_of(*found.array) + ", " + (shape.empty() ? "scalar" : shape) + ")";
}

// The arrays that are cubes (`cubes`) or all the others (`!cubes`), described; "none" if none.
std::string list(const std::vector<Found>& arrays, bool cubes) {
  std::string out;
  for (const Found& found : arrays)
    if (is_cube(*found.array) == cubes) out += (out.empty() ? "" : ", ") + describe(found);
  return out.empty() ? "none" : out;
}

std::string lower(std::string text) {
  for (char& c : text)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

// 0 inline, 1 crossline, 2 sample, -1 not recognised.
int axis_of(const std::string& dimension_name) {
  const std::string name = lower(dimension_name);
  // x and y (eastings and northings) as inline and crossline: the default affine takes the inline
  // axis east and the crossline axis north, so a map keeps its handedness.
  for (const char* n : {"iline", "inline", "inlines", "il", "x"})
    if (name == n) return 0;
  for (const char* n : {"xline", "crossline", "crosslines", "xl", "y"})
    if (name == n) return 1;
  for (const char* n : {"twt", "time", "depth", "z", "sample", "samples"})
    if (name == n) return 2;
  return -1;
}

std::vector<double> read_coordinates(const GDALMDArray& variable) {
  std::vector<double> values(static_cast<std::size_t>(variable.GetDimensions()[0]->GetSize()));
  const GUInt64 start = 0;
  const std::size_t count = values.size();
  if (!variable.Read(&start, &count, nullptr, nullptr, GDALExtendedDataType::Create(GDT_Float64), values.data()))
    return {};
  return values;
}

// The values of the dimension's 1-D numeric indexing variable, or empty.
std::vector<double> coordinates_of(const GDALDimension& dimension) {
  auto variable = dimension.GetIndexingVariable();
  if (!variable || variable->GetDimensionCount() != 1 || variable->GetDataType().GetClass() != GEDTC_NUMERIC ||
      variable->GetDimensions()[0]->GetSize() != dimension.GetSize() || dimension.GetSize() == 0)
    return {};
  return read_coordinates(*variable);
}

std::string unit_of(const GDALDimension& dimension) {
  auto variable = dimension.GetIndexingVariable();
  if (!variable) return {};
  std::string unit = variable->GetUnit();
  if (unit.empty())
    if (auto attribute = variable->GetAttribute("units"))
      if (const char* text = attribute->ReadAsString()) unit = text;
  return lower(unit);
}

// A cube is a regular grid: a coordinate variable must go in even steps, or it would place every
// sample after the first step wrongly. The tolerance lets coordinates stored as Float32 (seconds
// at 4 ms steps lose a few parts in ten thousand of a step by 8 s) through. Constant values (a
// placeholder some tools write) say nothing and are taken as no coordinates.
void check_even_steps(const std::vector<double>& values, const GDALDimension& dimension, const std::string& path) {
  if (values.size() < 3 || std::all_of(values.begin(), values.end(), [&](double v) { return v == values[0]; })) return;
  const double step = values[1] - values[0];
  double largest = 0.0;
  for (double v : values)
    largest = std::max(largest, std::abs(v));
  const double tolerance = 1e-3 * std::abs(step) + 1e-6 * largest;
  for (std::size_t n = 2; n < values.size(); ++n)
    if (!(std::abs(values[n] - values[n - 1] - step) <= tolerance))
      throw FormatError("the coordinate variable of dimension '" + dimension.GetName() + "' is not evenly spaced: " +
                            number_text(values[n - 1]) + " then " + number_text(values[n]) + " after a step of " +
                            number_text(step) + " (index " + std::to_string(n) + ")",
                        {path},
                        "geotandem reads regular grids, some of whose lines may be missing (steps that are whole "
                        "multiples of the smallest); resample the cube onto even steps");
}

// Line numbers that skip whole lines: every step a whole multiple (1 or more) of the smallest, all
// in one direction. The cube index of each stored line, or empty when they are not such a lattice.
std::vector<std::int64_t> lattice_of(const std::vector<double>& values, double& step) {
  if (values.size() < 3) return {};
  step = values[1] - values[0];
  for (std::size_t n = 1; n < values.size(); ++n) {
    const double d = values[n] - values[n - 1];
    if (!(d * step > 0.0)) return {}; // a turn, a repeated value or NaN
    if (std::abs(d) < std::abs(step)) step = d;
  }
  double largest = 0.0;
  for (double v : values)
    largest = std::max(largest, std::abs(v));
  const double tolerance = 1e-3 * std::abs(step) + 1e-6 * largest;
  std::vector<std::int64_t> grid{0};
  for (std::size_t n = 1; n < values.size(); ++n) {
    const double d = values[n] - values[n - 1];
    const double k = std::round(d / step);
    if (!(std::abs(d - k * step) <= tolerance)) return {};
    grid.push_back(grid.back() + static_cast<std::int64_t>(k));
  }
  return grid;
}

// "506, 507 and 510 (3 of 12 lines)": the line numbers the lattice skips (the first few).
std::string missing_lines_text(const std::vector<std::int64_t>& grid, double first, double step) {
  std::vector<std::int64_t> missing;
  std::size_t count = 0;
  for (std::size_t m = 1; m < grid.size(); ++m)
    for (auto g = grid[m - 1] + 1; g < grid[m]; ++g) {
      if (missing.size() < 6) missing.push_back(g);
      ++count;
    }
  std::string text;
  for (std::size_t n = 0; n < std::min<std::size_t>(missing.size(), 5); ++n)
    text += (n == 0           ? ""
             : n + 1 == count ? " and "
                              : ", ") +
            number_text(first + step * static_cast<double>(missing[n]));
  if (count > 5) text += " and " + std::to_string(count - 5) + " more";
  return text + " (" + std::to_string(count) + " of " + std::to_string(grid.back() + 1) + " lines)";
}

// First value and increment of a coordinate variable (increment kept at `step` for a single value);
// for a survey with missing lines also its number of lines and where the stored ones go.
void take_line_numbers(const std::vector<double>& values, const GDALDimension& dimension, const std::string& path,
                       bool read_missing, double& first, double& step, std::int64_t& count,
                       std::vector<std::int64_t>& grid, std::string& missing) {
  if (values.empty()) return;
  double lattice_step = 0.0;
  std::vector<std::int64_t> lattice = lattice_of(values, lattice_step);
  if (lattice.empty() || lattice.back() + 1 == static_cast<std::int64_t>(values.size())) {
    check_even_steps(values, dimension, path);
    first = values[0];
    if (values.size() > 1 && values[1] != values[0]) step = values[1] - values[0];
    return;
  }
  std::string skipped = missing_lines_text(lattice, values[0], lattice_step);
  const std::string what =
      "the line numbers of dimension '" + dimension.GetName() + "' skip lines, missing: " + skipped;
  // A few lines spread over a huge range are not a survey with some lines missing.
  if (lattice.back() + 1 > 4 * static_cast<std::int64_t>(values.size()))
    throw FormatError(what + ": more than three lines in four", {path},
                      "geotandem reads regular grids; resample the cube onto even steps");
  if (!read_missing)
    throw FormatError(what, {path},
                      "read the missing lines as missing samples with --nan fill (input.nan: fill in a recipe), "
                      "or write them into the file as NaN");
  first = values[0];
  step = lattice_step;
  count = lattice.back() + 1;
  missing = std::move(skipped);
  grid = std::move(lattice);
}

} // namespace

std::shared_ptr<GDALMDArray> choose_array(GDALGroup& root, const std::string& requested, const std::string& path) {
  std::vector<Found> arrays;
  collect(root, arrays, 0);
  if (!requested.empty()) {
    auto it = std::find_if(arrays.begin(), arrays.end(),
                           [&](const Found& f) { return f.full_name == requested || f.array->GetName() == requested; });
    if (it == arrays.end())
      throw FormatError("the file has no array named '" + requested + "'; cube candidates: " + list(arrays, true) +
                            "; other arrays: " + list(arrays, false),
                        {path}, "pass one of the candidates as the variable name");
    if (it->array->GetDimensionCount() != 3)
      throw FormatError("array " + describe(*it) + " has " + std::to_string(it->array->GetDimensionCount()) +
                            " dimensions; a cube needs 3 (inline, crossline, sample)",
                        {path}, "choose a 3-D array; candidates: " + list(arrays, true));
    if (!is_float(*it->array))
      throw FormatError("array " + describe(*it) +
                            " does not hold floating-point samples; geotandem reads Float32 "
                            "or Float64 cubes",
                        {path}, "convert the array to Float32");
    return it->array;
  }
  std::vector<const Found*> cubes;
  for (const Found& found : arrays)
    if (is_cube(*found.array)) cubes.push_back(&found);
  if (cubes.size() == 1) return cubes.front()->array;
  if (cubes.empty())
    throw FormatError("the file has no 3-D Float32 or Float64 array; arrays found: " + list(arrays, false), {path},
                      "a cube is a 3-D floating-point array (inline, crossline, sample); convert it to Float32");
  throw FormatError("the file has several 3-D floating-point arrays: " + list(arrays, true), {path},
                    "choose one with the variable option (--variable NAME, or input.variable in a recipe)");
}

std::shared_ptr<GDALMDArray> in_cube_order(const std::shared_ptr<GDALMDArray>& array, const std::string& path) {
  const auto& dims = array->GetDimensions();
  std::array<int, 3> position{-1, -1, -1}; // position[axis] = stored dimension holding that axis
  bool all_known = true;
  for (int d = 0; d < 3; ++d) {
    int axis = axis_of(dims[static_cast<std::size_t>(d)]->GetName());
    if (axis < 0 || position[static_cast<std::size_t>(axis)] >= 0) {
      all_known = false;
      continue;
    }
    position[static_cast<std::size_t>(axis)] = d;
  }
  if (!all_known) {
    // The stored order is taken as (inline, crossline, sample), unless a name says otherwise: a
    // sample axis named as such but stored before the last place (CF files put time or depth
    // first) would be read as a line of traces, every body in a transposed frame.
    if (position[2] >= 0 && position[2] != 2)
      throw FormatError("dimension '" + dims[static_cast<std::size_t>(position[2])]->GetName() + "' of array " +
                            array->GetFullName() + " is the sample axis by its name, stored as axis " +
                            std::to_string(position[2] + 1) + " of 3, and the other names (" +
                            dims[static_cast<std::size_t>(position[2] == 0 ? 1 : 0)]->GetName() + ", " +
                            dims[static_cast<std::size_t>(position[2] == 2 ? 1 : 2)]->GetName() +
                            ") do not say which is the inline and which the crossline axis",
                        {path}, "rename those dimensions iline and xline (or x and y), or store the sample axis last");
    return array;
  }
  if (position == std::array<int, 3>{0, 1, 2}) return array;
  auto view = array->Transpose({position[0], position[1], position[2]});
  return view ? view : array;
}

Geometry read_geometry(const GDALMDArray& array, const GDALMDArray& attributes_of, const std::string& path,
                       bool read_missing, LineGaps* gaps) {
  Geometry g;
  const auto& dims = array.GetDimensions();
  for (int a = 0; a < 3; ++a)
    g.shape[a] = static_cast<std::int64_t>(dims[static_cast<std::size_t>(a)]->GetSize());
  // Without better knowledge the indices are the line numbers.
  g.inline0 = 0.0;
  g.crossline0 = 0.0;
  LineGaps found;
  take_line_numbers(coordinates_of(*dims[0]), *dims[0], path, read_missing, g.inline0, g.inline_step, g.shape[0],
                    found.grid[0], found.missing[0]);
  take_line_numbers(coordinates_of(*dims[1]), *dims[1], path, read_missing, g.crossline0, g.crossline_step, g.shape[1],
                    found.grid[1], found.missing[1]);
  if (gaps) *gaps = std::move(found);

  const GDALDimension& z = *dims[2];
  const std::string unit = unit_of(z);
  if (unit == "m" || unit == "meter" || unit == "meters" || unit == "metre" || unit == "metres" ||
      (unit.empty() && lower(z.GetName()) == "depth"))
    g.z_unit = SampleUnit::metres;
  // Feet as the file says (UDUNITS names; US survey feet differ from feet by 2 parts in a million).
  if (unit == "ft" || unit == "foot" || unit == "feet" || unit == "international_foot" || unit == "us_survey_foot" ||
      unit == "ftus")
    g.z_unit = SampleUnit::feet;
  std::vector<double> zs = coordinates_of(z);
  if (unit == "s" || unit == "second" || unit == "seconds")
    for (double& value : zs)
      value *= 1000.0;
  check_even_steps(zs, z, path);
  // Samples go down the trace: a sample axis whose coordinates decrease (stored bottom up, or an
  // elevation) would put every body upside down.
  if (zs.size() > 1 && zs[1] < zs[0])
    throw FormatError("the sample axis '" + z.GetName() + "' decreases: " + number_text(zs[0]) + " then " +
                          number_text(zs[1]) + (unit.empty() ? "" : " " + unit),
                      {path},
                      "geotandem reads traces with time or depth increasing from the first sample; reverse that "
                      "axis of the cube (and make an elevation a depth) before reading it");
  if (!zs.empty()) g.z0 = zs[0];
  if (zs.size() > 1 && zs[1] > zs[0]) g.dz = zs[1] - zs[0];

  for (const GeometryField& field : geometry_fields())
    if (auto attribute = attributes_of.GetAttribute(field.key)) {
      if (attribute->GetDataType().GetClass() == GEDTC_NUMERIC) {
        field.field(g) = attribute->ReadAsDouble();
      } else if (auto value = parse_double(attribute->ReadAsString())) {
        field.field(g) = *value;
      } else {
        throw FormatError(std::string("attribute ") + field.key + " of array " + attributes_of.GetFullName() +
                              " is not a number",
                          {path}, "repair or remove the attribute");
      }
    }
  if (auto attribute = attributes_of.GetAttribute(z_unit_key)) {
    const char* text = attribute->ReadAsString();
    try {
      g.z_unit = parse_sample_unit(text ? text : "");
    } catch (const InvalidArgument&) {
      throw FormatError(std::string("attribute ") + z_unit_key + " is '" + (text ? text : "") +
                            "'; expected 'ms' or 'm'",
                        {path}, "repair the attribute");
    }
  }
  try {
    g.validate();
  } catch (const InvalidArgument& error) {
    throw FormatError("the geometry stored with array " + attributes_of.GetFullName() +
                          " is unusable: " + error.message(),
                      {path}, "repair the geotandem_* attributes or the coordinate variables");
  }
  return g;
}

namespace {

// The text of a string attribute, or "" when there is none or it holds no text.
std::string text_attribute(const GDALIHasAttribute& holder, const char* name) {
  auto attribute = holder.GetAttribute(name);
  if (!attribute || attribute->GetDataType().GetClass() != GEDTC_STRING) return {};
  const char* text = attribute->ReadAsString();
  return text ? text : "";
}

} // namespace

std::optional<Crs> read_crs(GDALGroup& root, const GDALMDArray& stored, const std::string& path) {
  const std::string array = stored.GetFullName();
  if (auto text = text_attribute(stored, crs_key); !text.empty())
    return crs_of_text(text, std::string("attribute ") + crs_key + " of array " + array, path);
  if (auto srs = stored.GetSpatialRef())
    if (auto crs = crs_of_srs(srs.get(), "the grid mapping of array " + array, path)) return crs;
  if (auto name = text_attribute(stored, "grid_mapping"); !name.empty())
    if (auto mapping = root.OpenMDArray(name))
      for (const char* key : {"crs_wkt", "spatial_ref"})
        if (auto text = text_attribute(*mapping, key); !text.empty())
          return crs_of_text(text, "attribute " + std::string(key) + " of the grid mapping variable " + name, path);
  if (auto text = text_attribute(stored, "crs"); !text.empty())
    return crs_of_text(text, "attribute crs of array " + array, path);
  if (auto text = text_attribute(root, "crs"); !text.empty())
    return crs_of_text(text, "attribute crs of the file", path);
  return std::nullopt;
}

} // namespace geotandem::volume::detail::gdal
