#pragma once
// An attribute is a volume computed from other volumes. It wraps its inputs, declares the halo it
// reads around any box, and computes a box on demand, so that attribute and extraction run fused,
// block by block; nothing computes or stores the whole attribute cube unless asked to.
//
// Box independence: the value at a voxel depends only on the inputs and the parameters, never on
// the box it was asked in. Where a halo leaves the cube, the input is extended by mirror
// reflection about the cube's faces (half-sample symmetric: index -1 reads 0, -2 reads 1, n reads
// n-1; repeated for halos wider than the cube). A box computed alone is therefore bit-identical to
// the same box cut from a whole-cube computation (tests/attributes check it).
//
// Inputs are expected to be finite (open_volume's NaN policy guarantees it); a NaN spreads to every
// output whose halo reaches it.
//
// Index space: filters work in samples along (inline, crossline, sample); the geometry's spacing is
// not used. Axis 2 (the sample axis, contiguous in memory) is "along the trace".
//
// Memory: a large box is computed in tiles (about kTile samples per axis, at most 5/4 of it, split
// evenly; each with its own halo) and assembled, so reading a whole cube needs a few tiles' worth of working memory,
// not a few cubes' worth. Tiles are box-independent like any other box, so the result is unchanged.
//
// Thread safety: read() keeps no state between calls, so an attribute may be read from several
// threads at once if its inputs may.

#include <memory>
#include <string>
#include <vector>

#include "geotandem/volume/volume.hpp"

namespace geotandem::attributes {

using volume::Box;
using volume::Geometry;
using volume::Index3;
using volume::Volume;

using VolumePtr = std::shared_ptr<const Volume>;

class Attribute : public Volume {
public:
  // The nominal tile computed at once (inline, crossline, sample) by attributes that use tiling.
  static constexpr Index3 kTile{64, 64, 256};
  // How many tiles a box of `n` samples along `axis` is cut into (each at most 5/4 kTile[axis]).
  static std::int64_t tiles_along(std::int64_t n, int axis);

  // The geometry of the (first) input: an attribute has the shape of what it is computed from.
  const Geometry& geometry() const override { return inputs_.front()->geometry(); }
  std::string format() const override { return "attribute " + name_; }
  // "chaos(formula=planarity, sigma_g=1, ...) of <the input's source>", for messages.
  std::string source() const override;

  // The attribute's name as recipes spell it ("envelope", "chaos", ...).
  const std::string& name() const { return name_; }
  // Samples read beyond a requested box on each side, per axis (inline, crossline, sample).
  const Index3& halo() const { return halo_; }
  // The halo down the whole chain to the stored data: own halo plus the largest total halo of the
  // inputs (what one box costs in reads of the source cube).
  Index3 total_halo() const;
  Index3 source_halo() const override { return total_halo(); }
  const std::vector<VolumePtr>& inputs() const { return inputs_; }

protected:
  enum class Tiling { tiles, whole_box };
  // Throws InvalidArgument if an input is null or if inputs differ in shape. Attributes that need no
  // working memory beyond the output (sample-by-sample combinators) pass Tiling::whole_box.
  Attribute(std::string name, std::string parameters, std::vector<VolumePtr> inputs, Index3 halo,
            Tiling tiling = Tiling::tiles);

  // Computes the samples of `box` (inside the cube, at most 5/4 kTile per axis unless whole_box) into
  // `out`, in the box's C order.
  virtual void compute(const Box& box, std::span<float> out) const = 0;

private:
  void read_box(const Box& box, std::span<float> out) const final;

  std::string name_;
  std::string parameters_;
  std::vector<VolumePtr> inputs_;
  Index3 halo_;
  Tiling tiling_;
};

} // namespace geotandem::attributes
