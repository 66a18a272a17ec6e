#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <vector>

#include "formats.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/core/output_path.hpp"
#include "geotandem/volume/crs.hpp"
#include "geotandem/volume/size_guard.hpp"
#include "raw_sidecar.hpp"

namespace fs = std::filesystem;

namespace geotandem::volume {
namespace detail {
namespace {

bool starts_with(const std::array<unsigned char, 16>& head, std::size_t got, std::string_view magic) {
  if (got < magic.size()) return false;
  for (std::size_t n = 0; n < magic.size(); ++n)
    if (head[n] != static_cast<unsigned char>(magic[n])) return false;
  return true;
}

std::string lower_extension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

bool envi_header_beside(const std::string& path) {
  for (const fs::path& hdr : {fs::path(path + ".hdr"), fs::path(path).replace_extension(".hdr")}) {
    std::error_code ec;
    if (!fs::is_regular_file(hdr, ec)) continue; // a FIFO would block
    std::ifstream in(hdr);
    std::string first;
    if (in && std::getline(in, first) && first.rfind("ENVI", 0) == 0) return true;
  }
  return false;
}

// Whether a 3200-byte block is text in one encoding: printable ASCII, or the printable EBCDIC
// characters (letters, digits, space and punctuation); NUL padding is allowed in both.
bool is_textual_header(const std::vector<unsigned char>& text) {
  const auto ascii = [](unsigned char c) { return c == 0 || (c >= 0x20 && c <= 0x7E); };
  const auto ebcdic = [](unsigned char c) {
    return c == 0 || c == 0x40 || (c >= 0x4A && c <= 0x50) || (c >= 0x5A && c <= 0x61) || (c >= 0x6A && c <= 0x6F) ||
           (c >= 0x79 && c <= 0x7F) || (c >= 0x81 && c <= 0x89) || (c >= 0x91 && c <= 0x99) ||
           (c >= 0xA1 && c <= 0xA9) || (c >= 0xC0 && c <= 0xC9) || (c >= 0xD0 && c <= 0xD9) ||
           (c >= 0xE0 && c <= 0xE9) || (c >= 0xF0 && c <= 0xF9);
  };
  return std::all_of(text.begin(), text.end(), ascii) || std::all_of(text.begin(), text.end(), ebcdic);
}

// SEG-Y has no magic number: a 3200-byte textual header (EBCDIC or ASCII, by convention starting
// with 'C', sometimes blank), a 400-byte binary header with a sample format code (1 to 16) at
// bytes 3225-3226 in the file's byte order (big-endian by the standard, little-endian in some
// files), then traces. A file whose first 3200 bytes are all text in one encoding is SEG-Y too
// whatever its code says (0, 17, 256: a damaged binary header), so that the SEG-Y reader names the
// code instead of "unknown format". Unsupported codes and the size are not checked here: such files
// must reach the SEG-Y reader, which says what is wrong.
bool looks_like_segy(const std::string& path, std::uintmax_t size) {
  if (size < 3600 + 240) return false;
  std::ifstream in(path, std::ios::binary);
  std::vector<unsigned char> text(3200);
  in.read(reinterpret_cast<char*>(text.data()), static_cast<std::streamsize>(text.size()));
  const unsigned char first = text[0];
  if (!in || (first != 0xC3 && first != 'C' && first != 0x40 && first != ' ')) return false;
  unsigned char code[2] = {0, 0};
  in.seekg(3224);
  in.read(reinterpret_cast<char*>(code), 2);
  const int big = code[0] << 8 | code[1], little = code[1] << 8 | code[0];
  return in && ((big >= 1 && big <= 16) || (little >= 1 && little <= 16) || is_textual_header(text));
}

// The writer for an output path, from its extension; nullptr when the extension is unknown.
using Writer = void (*)(const Volume&, const std::string&, const WriteOptions&, Progress&, const CancelToken&);

void write_netcdf(const Volume& v, const std::string& p, const WriteOptions& o, Progress& r, const CancelToken& c) {
  write_gdal_md(v, p, Format::netcdf, o, r, c);
}
void write_zarr(const Volume& v, const std::string& p, const WriteOptions& o, Progress& r, const CancelToken& c) {
  write_gdal_md(v, p, Format::zarr, o, r, c);
}

Writer writer_for(const std::string& ext) {
  if (ext == ".nc") return write_netcdf;
  if (ext == ".zarr") return write_zarr;
  if (ext == ".tif" || ext == ".tiff") return write_geotiff;
  if (ext == ".segy" || ext == ".sgy") return write_segy;
  if (ext == ".raw") return write_raw;
  return nullptr;
}

} // namespace

const char* format_name(Format format) {
  switch (format) {
  case Format::netcdf: return "netCDF-4";
  case Format::hdf5: return "HDF5";
  case Format::zarr: return "Zarr";
  case Format::geotiff: return "GeoTIFF";
  case Format::envi: return "ENVI";
  case Format::segy: return "SEG-Y";
  case Format::raw: return "raw";
  case Format::unknown: break;
  }
  return "unknown";
}

Format sniff_format(const std::string& path) {
  std::error_code ec;
  auto status = fs::status(path, ec);
  if (ec || !fs::exists(status))
    throw IoError("no such file or directory", {path}, "check the path; formats are found from the file itself");
  if (!fs::is_directory(status) && !fs::is_regular_file(status)) {
    // A FIFO or a device would block or never end; neither is a cube.
    const char* kind = fs::is_fifo(status)             ? "a FIFO (named pipe)"
                       : fs::is_character_file(status) ? "a character device"
                       : fs::is_block_file(status)     ? "a block device"
                       : fs::is_socket(status)         ? "a socket"
                                                       : "not a regular file";
    throw IoError(std::string("cannot read a cube from ") + kind, {path},
                  "give a cube file (or a Zarr directory); copy streamed data to a file first");
  }
  if (fs::is_directory(status)) {
    for (const char* marker : {".zgroup", ".zarray", "zarr.json"})
      if (fs::exists(fs::path(path) / marker)) return Format::zarr;
    throw FormatError("a directory that is not a Zarr store (no .zgroup, .zarray or zarr.json inside)", {path});
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError("cannot open the file for reading", {path}, "check its permissions");
  std::array<unsigned char, 16> head{};
  in.read(reinterpret_cast<char*>(head.data()), head.size());
  auto got = static_cast<std::size_t>(in.gcount());
  if (starts_with(head, got, "\x89HDF\r\n\x1a\n")) {
    std::string ext = lower_extension(path);
    return ext == ".h5" || ext == ".hdf5" || ext == ".he5" ? Format::hdf5 : Format::netcdf;
  }
  if (starts_with(head, got, std::string_view("CDF\x01", 4)) || starts_with(head, got, std::string_view("CDF\x02", 4)))
    return Format::netcdf;
  if (starts_with(head, got, std::string_view("II*\0", 4)) || starts_with(head, got, std::string_view("MM\0*", 4)) ||
      starts_with(head, got, std::string_view("II+\0", 4)) || starts_with(head, got, std::string_view("MM\0+", 4)))
    return Format::geotiff;
  // Files with a signature win over sidecars: a netCDF or TIFF with some other tool's FILE.json
  // beside it is still what its first bytes say. Raw float32 has no signature of its own.
  if (fs::exists(path + ".json")) return Format::raw;
  if (envi_header_beside(path)) return Format::envi;
  if (looks_like_segy(path, fs::file_size(path, ec))) return Format::segy;
  return Format::unknown;
}

} // namespace detail

NanPolicy parse_nan_policy(const std::string& text) {
  if (text == "error") return NanPolicy::error;
  if (text == "fill") return NanPolicy::fill;
  throw InvalidArgument("unknown NaN policy '" + text + "'", {},
                        "use 'error' (stop at the first NaN) or 'fill' (treat NaN as outside every body)");
}

std::string detect_format(const std::string& path) {
  auto format = detail::sniff_format(path);
  if (format == detail::Format::unknown)
    throw FormatError("unknown format: not netCDF/HDF5, Zarr, GeoTIFF, ENVI, SEG-Y, nor raw with a .json sidecar",
                      {path}, "convert the cube to one of these, or add FILE.json beside a raw float32 file");
  return detail::format_name(format);
}

std::unique_ptr<Volume> open_volume(const std::string& path, const OpenOptions& options) {
  using detail::Format;
  detect_format(path); // throws a clear error for missing or unknown files
  std::unique_ptr<Volume> volume;
  switch (auto format = detail::sniff_format(path)) {
  case Format::netcdf:
  case Format::hdf5:
  case Format::zarr: volume = detail::open_gdal_md(path, format, options); break;
  case Format::geotiff:
  case Format::envi: volume = detail::open_gdal_raster(path, format, options); break;
  case Format::segy: volume = detail::open_segy(path, options); break;
  case Format::raw: volume = detail::open_raw(path, options); break;
  case Format::unknown: break;
  }
  try {
    volume->geometry().validate();
  } catch (const InvalidArgument& e) {
    // The geometry came from the file, not from the caller: a broken file, not a bad argument.
    throw FormatError("the file describes an invalid geometry: " + e.message(), {path}, e.hint());
  }
  if (options.crs) volume = with_crs(std::move(volume), *options.crs);
  return detail::guard_nan(std::move(volume), options);
}

std::unique_ptr<Volume> open_gdal_dataset(GDALDataset* dataset, const std::string& name, const OpenOptions& options) {
  std::unique_ptr<Volume> volume = detail::open_gdal_dataset(dataset, name, options);
  try {
    volume->geometry().validate();
  } catch (const InvalidArgument& e) {
    throw FormatError("the dataset describes an invalid geometry: " + e.message(), {name}, e.hint());
  }
  if (options.crs) volume = with_crs(std::move(volume), *options.crs);
  return detail::guard_nan(std::move(volume), options);
}

void check_output_format(const std::string& path) {
  const std::string ext = detail::lower_extension(path);
  if (!detail::writer_for(ext))
    throw InvalidArgument("cannot tell the output format from the extension '" + ext + "'", {path},
                          "use .nc (netCDF-4), .zarr, .tif (GeoTIFF), .segy or .raw");
}

void write_volume(const Volume& volume, const std::string& path, const WriteOptions& options, Progress* progress,
                  const CancelToken& cancel) {
  NullProgress silent;
  Progress& report = progress ? *progress : silent;
  const std::string ext = detail::lower_extension(path);
  if (options.chunk < 1) throw InvalidArgument("chunk size must be at least 1", {path});
  // Resolve the writer before touching anything: an unknown extension must not cost the user the
  // file that already sits at `path`.
  check_output_format(path);
  const detail::Writer writer = detail::writer_for(ext);
  std::error_code ec;
  // Nothing is written inside a component store but by the store.
  for (auto dir = fs::weakly_canonical(fs::absolute(path, ec), ec).parent_path(); !dir.empty();
       dir = dir.parent_path()) {
    if (fs::is_regular_file(dir / "store.json", ec) && fs::exists(dir / "index.sqlite", ec))
      throw InvalidArgument("will not write a cube inside a component store (" + dir.string() + ")", {path},
                            "write it outside the store directory");
    if (dir == dir.root_path()) break;
  }
  // Refused before anything is written or removed when the disk cannot hold the cube.
  check_disk_fits(volume.geometry().shape, path, "the cube");
  if (fs::exists(fs::symlink_status(path, ec))) {
    if (!options.overwrite) throw IoError("the output already exists", {path}, "remove it or pass --overwrite");
    require_replaceable(path, ext == ".zarr"); // a Zarr store is a directory
    fs::remove_all(path, ec);
    if (ec) throw IoError("cannot remove the existing output: " + ec.message(), {path});
  }
  // A stale raw sidecar would describe the old cube until the new one is complete.
  if (ext == ".raw") {
    require_replaceable(path + ".json");
    fs::remove(path + ".json", ec);
  }
  writer(volume, path, options, report, cancel);
}

void write_segy_like(const Volume& volume, const std::string& like, const OpenOptions& like_options,
                     const std::string& path, const WriteOptions& options, Progress* progress,
                     const CancelToken& cancel) {
  NullProgress silent;
  check_disk_fits(volume.geometry().shape, path, "the cube");
  detail::write_segy_like(volume, like, like_options, path, options, progress ? *progress : silent, cancel);
}

std::unique_ptr<Volume> apply_nan_policy(std::unique_ptr<Volume> volume, const OpenOptions& options) {
  return detail::guard_nan(std::move(volume), options);
}

void write_raw_sidecar(const std::string& path, const Geometry& geometry) {
  geometry.validate();
  const std::string sidecar = detail::raw_sidecar_of(path);
  std::ofstream out(sidecar, std::ios::trunc);
  out << detail::raw_sidecar_text(geometry);
  out.flush();
  if (!out) throw IoError("cannot write the raw sidecar", {sidecar}, "check that the directory is writable");
}

} // namespace geotandem::volume
