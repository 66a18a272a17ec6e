#pragma once
// The label cube (issue 54, part 3): every sample of the extracted field gets the body ID of the
// kept body it lies in (0 outside every kept body), on the field's grid, for interpretation
// packages that work with voxel bodies (OpendTect's voxel connectivity filter, DUG Insight).
//
// A body is a connected component of the inside samples (value >= iso, or <= iso with the side
// below; NaN outside) under 6-adjacency: the connectivity of marching cubes' inside with its face
// rule (docs/marching-cubes.md), so a body's samples are exactly those its surface encloses,
// less any cavities (outside samples, 0 here, and their own surfaces in the store).
//
// Store key to body: a key is the smallest lattice id of a vertex born in the component
// (mesh::Component::key). An edge id names a crossed lattice edge, one end inside and one
// outside: the inside end is a sample of the body. A cap id (LatticeIds::sample_id) names an
// inside sample on the cube's border. So each kept key seeds exactly one body; a body seeded by
// several kept keys (its outer surface and a cavity's) is labelled once, by its smallest key.
// A key whose edge is not crossed by the field is refused: the store was made from other data.
//
// How (docs/label-cube.md): two passes over slabs of whole inlines, memory bounded like the
// extraction's marching cubes (one slab of values and labels of at most `slab_samples` samples).
// Pass 1 labels each slab's 6-connected components with a union-find, joins them to the previous
// slab's last inline, and keeps a global union-find over the slabs' provisional labels (about 24
// bytes per provisional label) with each one's seed keys and sample count. Pass 2 (reads of this
// volume) labels each slab again in the same way and maps its provisional labels to body IDs.

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "geotandem/core/cancel.hpp"
#include "geotandem/core/progress.hpp"
#include "geotandem/volume/io.hpp"
#include "geotandem/volume/volume.hpp"

namespace geotandem::workflow {

struct LabelSettings {
  float iso = 0.0f;
  bool below = false; // side below: inside means value <= iso
  // Samples of one slab of whole inlines (at least one inline), as marching cubes' slab budget.
  std::int64_t slab_samples = std::int64_t{1} << 23;
};

struct LabelledBody {
  std::uint32_t id = 0;            // the label, 1..N in increasing key order
  std::uint64_t key = 0;           // the smallest kept store key on its boundary
  std::vector<std::uint64_t> keys; // every kept key on its boundary (sorted; keys.front() == key)
  std::uint64_t samples = 0;       // its labelled samples
};

// The label cube of `field` as a lazy volume: the constructor runs pass 1, reads run pass 2.
// IDs are float32 samples (exact up to 2^24 bodies; more is refused). Reads are fastest in
// increasing inline order; a read spanning many inlines holds their labels at once (4 bytes per
// sample of the inlines it spans). Throws DataError when a key does not seed a body of the field
// (another cube, iso or side), InvalidArgument when the iso is NaN, Cancelled, and what the field's
// reads throw.
class LabelCube final : public volume::Volume {
public:
  LabelCube(std::shared_ptr<const volume::Volume> field, const LabelSettings& settings, std::vector<std::uint64_t> keys,
            Progress* progress = nullptr, const CancelToken& cancel = {});
  ~LabelCube() override;

  const volume::Geometry& geometry() const override;
  std::string format() const override { return "label cube"; }
  std::string source() const override;
  const std::vector<LabelledBody>& bodies() const;
  // Provisional labels of pass 1 (the global union-find's size), for the memory figures.
  std::uint64_t provisional_labels() const;

protected:
  void read_box(const volume::Box& box, std::span<float> out) const override;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The input file a label cube follows: its format family, and for SEG-Y its headers (every trace
// header is copied). `file` empty: no file (a synthetic cube, an array): any format goes.
struct LabelLike {
  std::string file;
  // How the file was read: the SEG-Y header bytes that place its traces (and its missing bins,
  // under nan_policy fill), as the extraction read it.
  volume::OpenOptions options;
};

// The input of a chain (a recipe's run, or a store's run that recorded its chain) as a LabelLike.
LabelLike label_like_of_input(const nlohmann::json& chain_input);

// The extensions of the input's format family, the first being the usual one: SEG-Y .segy/.sgy,
// netCDF-4 and HDF5 .nc, Zarr .zarr, raw .raw, GeoTIFF and ENVI .tif; empty for no file (any
// format). Throws what detect_format throws.
std::vector<std::string> label_extensions(const LabelLike& like);
// Throws InvalidArgument, naming the extension to use, unless `path`'s extension is of the family
// of `like`'s file (any writable format when there is no file).
void check_label_format(const LabelLike& like, const std::string& path);

struct LabelOutput {
  std::string cube;  // the label cube's path
  std::string table; // PATH.bodies.csv: id,key,samples,keys
  std::string json;  // PATH.bodies.json: the same with iso, side, selection and store
  std::vector<LabelledBody> bodies;
  double seconds_label = 0.0; // pass 1
  double seconds_write = 0.0; // pass 2 and the writing
};

// Writes the label cube of `field` to `path`, in the format family of `like`'s file
// (check_label_format; the extension picks among write_volume's formats): a SEG-Y input gives a
// copy of its file with the labels as samples (volume::write_segy_like: every header kept, `note`
// on a textual header card); netCDF, Zarr, GeoTIFF and raw inputs the same format with the grid's
// coordinates (the raw sidecar). Whole or not at all (a temporary beside it, renamed into place),
// then its table beside it: PATH.bodies.csv and PATH.bodies.json. `description` (a JSON object:
// store, selection, ...) goes into the JSON table. An existing output is refused unless
// `overwrite`. Throws what LabelCube and the writers throw.
LabelOutput write_label_cube(std::shared_ptr<const volume::Volume> field, const LabelSettings& settings,
                             const std::vector<std::uint64_t>& keys, const LabelLike& like, const std::string& path,
                             bool overwrite, const nlohmann::json& description, const std::string& note,
                             Progress* progress, const CancelToken& cancel);

} // namespace geotandem::workflow
