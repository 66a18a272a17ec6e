#pragma once
// A lazy 3D scalar field. Consumers ask for a box (a block plus the halo they need) and never load
// a whole cube unless it is small. Attributes and synthetic cubes are volumes too: they compute any
// box on demand.

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "geotandem/core/cancel.hpp"
#include "geotandem/core/progress.hpp"
#include "geotandem/volume/box.hpp"
#include "geotandem/volume/geometry.hpp"

namespace geotandem::volume {

// A fact about how a file encodes its cube, worth showing a user: key "sample_format", value
// "16-bit integer (code 3)". Keys are snake_case (JSON); values are text for people.
struct FormatDetail {
  std::string key;
  std::string value;
  bool operator==(const FormatDetail&) const = default;
};
// The key of the no-data value a file declares: its samples with that value read as NaN (missing).
inline constexpr const char* kNoDataDetail = "no_data_value";

class Volume;
// The facts among a volume's format details that a command should print as warnings when it opens
// the cube, as "PATH: text": geographic trace coordinates made local metres ("coordinates"), what
// the file does not say and was assumed ("assumed"), lines missing from the survey
// ("missing_lines"), chunks that reads by blocks decode many times over ("slow_reads").
std::vector<std::string> open_warnings(const Volume& volume);

class Volume {
public:
  virtual ~Volume() = default;

  virtual const Geometry& geometry() const = 0;

  // Writes the samples of `box` into `out` in the box's C order (see box.hpp).
  // Preconditions: `box` lies inside geometry().bounds() and out.size() == box.count();
  // throws InvalidArgument naming the box and the cube's shape otherwise, IoError or FormatError
  // when the underlying file cannot deliver the samples.
  // Thread safety: not required; use one Volume per thread unless a subclass says otherwise.
  void read(const Box& box, std::span<float> out) const;
  std::vector<float> read(const Box& box) const;

  // Short format name ("netCDF-4", "Zarr", "SEG-Y", "raw", "synthetic analytic", ...).
  virtual std::string format() const = 0;
  // Where the samples come from, for messages: a path, or the parameters of a computed volume.
  virtual std::string source() const = 0;
  // Format-specific facts in display order (SEG-Y: sample format, byte order, header bytes);
  // empty for formats with nothing to add.
  virtual std::vector<FormatDetail> format_details() const { return {}; }
  // A value the file declares as no data (GeoTIFF's nodata, netCDF's _FillValue, ...), as its float
  // samples hold it. Reading does not change such samples; open_volume's NaN policy treats them as
  // missing, as it does NaN samples.
  virtual std::optional<float> declared_no_data() const { return std::nullopt; }
  // Samples a read of a box reaches beyond it, per axis and side, in the data this volume is
  // computed from (down to the stored or generated cube): 0 for stored data; an attribute chain
  // says its total halo. A hint for caches that fetch a box's sources at once (a volume that does
  // not know says 0: a cache then fetches too little, and the rest is read directly).
  virtual Index3 source_halo() const { return {0, 0, 0}; }
  // What opening this file again needs and opening it found (OpenOptions::reopen_hint): another
  // process that opens the same file with it skips that work. Empty when there is nothing worth
  // passing on. Two kinds of volume have one: a SEG-Y survey whose grid took a pass over every
  // trace header (irregular, or padded with placeholders), and a file read from its copy for reads
  // by blocks (use_block_copy).
  virtual std::string reopen_hint() const { return {}; }
  // For a file whose chunks reads by blocks decode many times over (the format detail
  // "slow_reads"): copies the cube once, reading each chunk once, into `directory` as raw float32
  // (FILE.raw + FILE.raw.json, named after the file and a digest of its content fingerprint), or
  // takes the complete copy already there for the file as it is now, and reads the copy from then on;
  // reopen_hint() then names it, so that other processes opening the file read it too. Returns the
  // copy's path; empty when the volume has no such layout (nothing is written). Throws IoError
  // when the copy cannot be written (a full disk; nothing is left behind and the volume still
  // reads the file) and Cancelled. Call it before reads run on other threads.
  virtual std::string use_block_copy(const std::string& directory, Progress* progress,
                                     const CancelToken& cancel) const {
    (void)directory, (void)progress, (void)cancel;
    return {};
  }

protected:
  // Called by read() after the box was checked.
  virtual void read_box(const Box& box, std::span<float> out) const = 0;
};

// A volume that holds its samples in memory (tests, small cubes, results of a whole-cube
// computation).
class MemoryVolume final : public Volume {
public:
  MemoryVolume(Geometry geometry, std::vector<float> samples, std::string source = "memory");
  // Reads a whole volume into memory.
  static std::unique_ptr<MemoryVolume> copy_of(const Volume& volume);

  const Geometry& geometry() const override { return geometry_; }
  std::string format() const override { return "memory"; }
  std::string source() const override { return source_; }
  const std::vector<float>& samples() const { return samples_; }
  std::vector<float>& samples() { return samples_; }

protected:
  void read_box(const Box& box, std::span<float> out) const override;

private:
  Geometry geometry_;
  std::vector<float> samples_;
  std::string source_;
};

} // namespace geotandem::volume
