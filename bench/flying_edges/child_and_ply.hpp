#pragma once
// bench_flying_edges_meshopt's plumbing: a child process timed by wait4, and the binary PLY that
// `geotandem store export --format ply` writes, read back.
#include <filesystem>
#include <string>
#include <vector>

#include "flying_edges/surface_distance.hpp"

namespace geotandem::bench {

struct Timing {
  double wall = 0.0; // s
  double cpu = 0.0;  // s, user + system
};

// Runs `argv` with stdout and stderr into files; its wall time and its CPU time (wait4's rusage of
// the child). Throws when it cannot start or does not exit with 0, quoting its stderr's end.
Timing run_child(const std::vector<std::string>& argv, const std::filesystem::path& out,
                 const std::filesystem::path& err);
// A whole file as text.
std::string read_text(const std::filesystem::path& path);
// A binary little-endian PLY with x, y, z vertex properties (float or double, any others skipped)
// and one face list (uchar or uint count, int or uint indices) plus scalar properties.
Surface read_ply(const std::filesystem::path& path);

} // namespace geotandem::bench
