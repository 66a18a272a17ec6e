#pragma once
// What an output may replace when the user allows it (--overwrite): a regular file, or a symbolic
// link (the link is replaced, not what it points to), and a directory only where the output is
// one (a Zarr store). A device, a FIFO or a socket at that path is never an earlier output: the
// writers used to remove it and put a file in its place (as root, `--out /dev/null --overwrite`
// replaced the device).

#include <filesystem>

namespace geotandem {

// Throws IoError naming what is at `path` when it exists and is none of those; does nothing when
// nothing is there.
void require_replaceable(const std::filesystem::path& path, bool directory_allowed = false);

} // namespace geotandem
