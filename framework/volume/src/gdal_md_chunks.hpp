#pragma once
// How a multidimensional array is chunked, and what that does to reads by blocks
// (docs/formats-gdal.md, "Chunks" and "The copy for reads by blocks"). The extraction reads the
// cube in blocks of about kBlockEdge samples an axis (its default leaf; the attributes' halos add
// a few), and a chunk is read, and decoded when compressed, by every block it spans. Whole inline
// slices (netCDF's default chunking for an unlimited first dimension, as a tool writing inline by
// inline leaves a file) are read by every block of a slice: 16 times at 512^3, 64 at 1024^3. Such a
// file is copied once as raw float32 (GdalMdVolume::use_block_copy, gdal_md.cpp); this file holds
// the layout, the warning and how the copy reads the file.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <gdal_priv.h>

#include "geotandem/volume/box.hpp"

namespace geotandem::volume::detail {

constexpr double kBlockEdge = 128.0;
// From this many reads of each chunk on, opening the file warns (format detail "slow_reads") and
// a run copies it for block reads (Volume::use_block_copy).
constexpr double kSlowReads = 8.0;
// The copy reads slabs of whole chunks; a layout whose thinnest such slab is larger than this is
// left as it is (only warned about).
constexpr double kMaxSlabBytes = 1024.0 * 1024.0 * 1024.0;
// How reopen_hint() names the copy.
constexpr const char* kCopyHint = "block copy: ";

struct ChunkLayout {
  std::string text;                    // "1 x 512 x 512 samples (iline x xline x twt), deflate"; empty: contiguous
  double reads_per_chunk = 1;          // blocks of kBlockEdge^3 that read each chunk
  std::vector<std::string> dimensions; // stored order
  Index3 cube_chunk{0, 0, 0};          // the chunk's extent in cube order, clipped to the cube; 0: not said
};

// The layout of `stored`, whose cube-order view is `cube` (gdal::in_cube_order).
ChunkLayout chunk_layout(const GDALMDArray& stored, const GDALMDArray& cube);

// The warning for a layout that blocks read many times over: what run-workflow and extract do
// about it (`copy_bytes`: the size of the copy they make; 0 when the layout allows none) and how to
// rewrite the file (`format`: format_name of the file's format).
std::string slow_reads_text(const ChunkLayout& layout, const std::string& format, double copy_bytes);

// How use_block_copy reads the file: slabs `thickness` samples thick along cube axis `axis`, a
// whole number of chunks thick, so that each chunk is decoded once; the axis whose chunk-thick
// slab is smallest (one inline slice for inline-slice chunks, one time slice for time slices).
// Along the sample axis the copy is written in runs as long as the slab is thick, so the slab
// takes up to kMaxSlabBytes / 4 of chunks. axis -1: no copy (the layout reads well by blocks, or
// even one slab would exceed kMaxSlabBytes).
struct CopySlabs {
  int axis = -1;
  std::int64_t thickness = 0;
};
CopySlabs copy_slabs(const ChunkLayout& layout, const Index3& shape);

// The copy's file name: the file's name with a digest of its content fingerprint (size,
// modification time, sampled checksum: volume::input_fingerprint) and of the array read, so that a
// copy is only ever taken for the file it was made from, as it is now.
std::string copy_name(const std::string& path, const std::string& array_name);

} // namespace geotandem::volume::detail
