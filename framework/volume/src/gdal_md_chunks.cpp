// Chunk layouts of multidimensional arrays and the copy for reads by blocks (gdal_md_chunks.hpp).
#include "gdal_md_chunks.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "formats.hpp"
#include "geotandem/volume/fingerprint.hpp"

namespace geotandem::volume::detail {

ChunkLayout chunk_layout(const GDALMDArray& stored, const GDALMDArray& cube) {
  ChunkLayout out;
  const std::vector<GUInt64> chunks = stored.GetBlockSize();
  const auto& dims = stored.GetDimensions();
  if (chunks.size() != dims.size() || std::find(chunks.begin(), chunks.end(), GUInt64{0}) != chunks.end())
    return out; // contiguous (read in place, never decoded whole) or not said
  std::string sizes, names;
  for (std::size_t d = 0; d < dims.size(); ++d) {
    const GUInt64 extent = std::min(chunks[d], dims[d]->GetSize());
    out.reads_per_chunk *= std::ceil(static_cast<double>(extent) / kBlockEdge);
    out.dimensions.push_back(dims[d]->GetName());
    sizes += (d ? " x " : "") + std::to_string(chunks[d]);
    names += (d ? " x " : "") + out.dimensions.back();
  }
  out.text = sizes + " samples (" + names + ")";
  CSLConstList info = stored.GetStructuralInfo();
  if (const char* method = CSLFetchNameValue(info, "COMPRESS")) {
    std::string lower = method;
    std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
    out.text += ", " + lower;
  } else if (CSLFetchNameValue(info, "COMPRESSOR")) {
    out.text += ", compressed";
  }
  // The same chunks seen in cube order: the view transposes them.
  const std::vector<GUInt64> seen = cube.GetBlockSize();
  const auto& cube_dims = cube.GetDimensions();
  if (seen.size() == 3 && cube_dims.size() == 3)
    for (std::size_t a = 0; a < 3; ++a) {
      const GUInt64 n = cube_dims[a]->GetSize();
      out.cube_chunk[a] = static_cast<std::int64_t>(seen[a] == 0 ? n : std::min(seen[a], n));
    }
  return out;
}

std::string slow_reads_text(const ChunkLayout& layout, const std::string& format, double copy_bytes) {
  std::string text = "stored in chunks of " + layout.text + ": blocks of " +
                     std::to_string(static_cast<int>(kBlockEdge)) + " samples an axis read each chunk about " +
                     std::to_string(static_cast<long long>(layout.reads_per_chunk)) + " times";
  if (copy_bytes > 0) {
    char size[32];
    if (copy_bytes < 1024.0 * 1024.0 * 1024.0)
      std::snprintf(size, sizeof size, "%.0f MiB", copy_bytes / (1024.0 * 1024.0));
    else
      std::snprintf(size, sizeof size, "%.1f GiB", copy_bytes / (1024.0 * 1024.0 * 1024.0));
    text += std::string("; run-workflow and extract copy it once (") + size +
            " of raw float32 beside their output, removed at the end) and read the copy";
  }
  text += "; rewriting the file once in chunks of about 64 samples an axis saves that";
  if (format == format_name(Format::netcdf)) {
    std::string spec;
    for (const std::string& name : layout.dimensions)
      spec += (spec.empty() ? "" : ",") + name + "/64";
    text += " (netCDF-4: nccopy -c " + spec + " IN.nc OUT.nc, from Debian's netcdf-bin)";
  }
  return text;
}

CopySlabs copy_slabs(const ChunkLayout& layout, const Index3& shape) {
  CopySlabs best;
  if (layout.reads_per_chunk < kSlowReads || layout.cube_chunk[0] == 0) return best;
  const double samples = static_cast<double>(shape[0]) * static_cast<double>(shape[1]) * static_cast<double>(shape[2]);
  double least = kMaxSlabBytes;
  for (int axis = 0; axis < 3; ++axis) {
    const auto a = static_cast<std::size_t>(axis);
    const std::int64_t n = shape[a], c = layout.cube_chunk[a];
    const double bytes = static_cast<double>(c) * samples / static_cast<double>(n) * sizeof(float);
    if (bytes > least || (best.axis >= 0 && bytes == least)) continue; // ties: the slower axis
    least = bytes;
    std::int64_t thickness = c;
    if (axis == 2)
      thickness = std::min(n, c * std::max<std::int64_t>(1, static_cast<std::int64_t>(kMaxSlabBytes / 4 / bytes)));
    best = {axis, thickness};
  }
  return best;
}

std::string copy_name(const std::string& path, const std::string& array_name) {
  const std::string identity = input_fingerprint(path).dump() + "\n" + array_name;
  std::uint64_t hash = 14695981039346656037ull; // FNV-1a
  for (unsigned char c : identity) {
    hash ^= c;
    hash *= 1099511628211ull;
  }
  char digest[17];
  std::snprintf(digest, sizeof digest, "%016llx", static_cast<unsigned long long>(hash));
  std::filesystem::path file = std::filesystem::path(path).lexically_normal();
  if (file.filename().empty()) file = file.parent_path(); // a Zarr directory given as "cube.zarr/"
  return file.filename().string() + "." + digest + ".raw";
}

} // namespace geotandem::volume::detail
