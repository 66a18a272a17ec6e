#pragma once
// Opening and writing cubes. The format is found from the file itself (signature, sidecar,
// directory layout), never from a flag.
//
// Readers: netCDF-4 / HDF5 / Zarr through GDAL's multidimensional API; GeoTIFF and ENVI through
// GDAL's classic raster API (time-slice stacks: one band per sample, raster x/y = inline/crossline;
// files geotandem wrote itself say so in their metadata and keep their inline-slice layout); SEG-Y
// through segyio (sample formats 1, 2, 3, 5, 8, either byte order); raw float32 with a JSON
// sidecar (FILE.raw + FILE.raw.json).
// Writers (format from the extension): .nc (netCDF-4), .zarr (Zarr v2), .tif (GeoTIFF, one band
// per inline), .segy/.sgy (SEG-Y rev 1, IEEE floats), .raw (+ .raw.json).
// CRS: read from netCDF/Zarr (geotandem_crs, a CF grid_mapping, a `crs` attribute), GeoTIFF/ENVI
// (their georeference, or geotandem_crs) and raw sidecars; written by every writer but SEG-Y's.

#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>

#include "geotandem/core/cancel.hpp"
#include "geotandem/core/progress.hpp"
#include "geotandem/volume/segy_options.hpp"
#include "geotandem/volume/volume.hpp"

class GDALDataset; // GDAL's dataset handle (gdal_priv.h)

namespace geotandem::volume {

// What to do with NaN or infinite samples.
enum class NanPolicy {
  error, // default: DataError naming the file, the box and the first bad sample's index
  fill,  // replace them by OpenOptions::fill_value (default: lowest float, i.e. "outside")
};
NanPolicy parse_nan_policy(const std::string& text);

struct OpenOptions {
  NanPolicy nan_policy = NanPolicy::error;
  float fill_value = std::numeric_limits<float>::lowest();
  // Samples equal to this value are missing too, as NaN samples and those equal to the no-data value
  // a GDAL file declares are (the policy above applies): the null of a SEG-Y or raw cube, which
  // cannot declare one (-999.25 is common).
  std::optional<float> no_data;
  // For multidimensional files with several 3D arrays: the array's name (empty: the only 3D one).
  std::string variable;
  // SEG-Y: where the trace headers keep line numbers and coordinates (segy_options.hpp).
  SegyOptions segy;
  // Where long work while opening reports how far it got: the pass over every trace header of an
  // irregular SEG-Y survey (a few seconds per ten million traces, more on a network file system).
  // Not owned; null: nowhere.
  Progress* progress = nullptr;
  // Volume::reopen_hint of the same file opened with the same options, by another process (the
  // manager, for its workers). Used only while it still describes the file (same size and
  // modification time, same header bytes); ignored otherwise, and by formats that have none.
  std::string reopen_hint;
  // The coordinate reference system of the map coordinates (volume::parse_crs), replacing what
  // the file says (input.crs, --crs). nullopt: the file's, if it says one.
  std::optional<Crs> crs;
};

// Opens a cube; throws IoError (missing, unreadable) or FormatError (unknown or broken format),
// naming the file and what to do.
std::unique_ptr<Volume> open_volume(const std::string& path, const OpenOptions& options = {});

// A cube held by a GDAL multidimensional dataset that the caller has already opened or built, with
// any driver: MEM (GDAL's in-memory driver, how other programs hand over arrays without a file),
// or a netCDF/Zarr/HDF5 dataset opened with options of their own. Takes ownership of `dataset` (it is
// closed with the volume, also on error). `name` stands for the file in messages and source().
// Geometry, array choice and the NaN policy are as for open_volume. Throws FormatError when the
// dataset holds no usable cube.
std::unique_ptr<Volume> open_gdal_dataset(GDALDataset* dataset, const std::string& name,
                                          const OpenOptions& options = {});

// The format open_volume would use for `path` ("netCDF-4", "Zarr", "SEG-Y", ...), or throws.
std::string detect_format(const std::string& path);

struct WriteOptions {
  // Chunk edge used for chunked formats and for the streaming block size (samples).
  int chunk = 64;
  std::string variable = "amplitude";
  bool overwrite = false;
  // A line saying what the cube holds, kept where the format has room for it: a card of the SEG-Y
  // textual header (upper-cased, at most 75 characters). Empty: nothing.
  std::string note;
};

// Throws InvalidArgument (listing the known extensions) when write_volume could not tell the
// format of `path` from its extension; recipes check their outputs with it before any work.
void check_output_format(const std::string& path);

// Streams `volume` into a new file, block by block (never the whole cube in memory). The format
// comes from the extension of `path`; an unknown extension is an InvalidArgument that lists the
// known ones. An existing file is an error unless options.overwrite.
void write_volume(const Volume& volume, const std::string& path, const WriteOptions& options = {},
                  Progress* progress = nullptr, const CancelToken& cancel = {});

// Writes `volume` into a new SEG-Y file at `path` that is the SEG-Y file `like` trace for trace:
// its textual header (with options.note on a blank card, in the header's own encoding), binary
// header, extended textual headers, and every trace header with its extensions, in the file's
// trace order and byte order; only the samples are `volume`'s, as IEEE floats (binary header
// format code 5). `volume` must have the grid open_volume(like, like_options) reads (the bins of
// missing traces are not written; placeholders outside the grid keep zero samples). Data after
// the last trace (rev 2 trailer stanzas) is not copied. An existing file at `path` is refused; a
// failed or cancelled write removes what it wrote. Throws IoError, FormatError (the file's own
// reading), InvalidArgument (another grid).
void write_segy_like(const Volume& volume, const std::string& like, const OpenOptions& like_options,
                     const std::string& path, const WriteOptions& options = {}, Progress* progress = nullptr,
                     const CancelToken& cancel = {});

// For programs that hand over samples of their own (the Python binding's numpy arrays): the NaN
// policy of `options` (nan_policy, fill_value, no_data) over any volume, as open_volume applies it
// to the files it reads.
std::unique_ptr<Volume> apply_nan_policy(std::unique_ptr<Volume> volume, const OpenOptions& options);

// Writes the JSON sidecar (PATH.json) that makes the float32 file PATH, written by another program
// in the raw layout (little-endian, C order [inline][crossline][sample]), a raw cube of geometry
// `geometry`. Throws IoError when it cannot be written.
void write_raw_sidecar(const std::string& path, const Geometry& geometry);

} // namespace geotandem::volume
