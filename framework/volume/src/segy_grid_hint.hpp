#pragma once
// What the pass over every trace header of a SEG-Y file found (its grid), as text that another
// process opening the same file takes instead of making that pass again (Volume::reopen_hint).

#include <cstdint>
#include <optional>
#include <string>

#include "segy_grid.hpp"

namespace geotandem::volume::detail::segy {

// A file's size and modification time: what says that a grid found earlier still describes it.
struct FileStamp {
  std::uintmax_t size = 0;
  std::int64_t modified_ns = 0;
  bool operator==(const FileStamp&) const = default;
};
// Throws IoError naming the file when it cannot be examined.
FileStamp file_stamp(const std::string& path);

// An irregular grid as text (Volume::reopen_hint), so that other processes opening the same file
// skip the pass over every trace header: its numbers, affine and stamp, and its traces as runs of
// consecutive traces whose bins follow at a constant step (about one run per line of a survey with
// a ragged outline), none for a survey padded with placeholders. Empty for a grid found from a few
// headers, and when the runs are short (holes everywhere).
std::string grid_hint(const Grid& grid, const FileStamp& stamp);
// The grid of a hint, when the hint is well formed, for this stamp and these header bytes, and
// places each of the file's `traces` traces once; nothing otherwise (the grid is then found as
// usual). Reading still checks every trace's line numbers against its place.
std::optional<Grid> grid_from_hint(const std::string& hint, const FileStamp& stamp, const SegyOptions& bytes,
                                   int traces);

} // namespace geotandem::volume::detail::segy
