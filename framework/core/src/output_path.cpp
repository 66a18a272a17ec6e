#include "geotandem/core/output_path.hpp"

#include <string>

#include "geotandem/core/error.hpp"

namespace geotandem {

void require_replaceable(const std::filesystem::path& path, bool directory_allowed) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::symlink_status(path, ec);
  if (ec || !fs::exists(status) || fs::is_regular_file(status) || fs::is_symlink(status)) return;
  if (fs::is_directory(status) && directory_allowed) return;
  const char* kind = fs::is_directory(status)        ? "a directory"
                     : fs::is_fifo(status)           ? "a FIFO (named pipe)"
                     : fs::is_character_file(status) ? "a character device"
                     : fs::is_block_file(status)     ? "a block device"
                     : fs::is_socket(status)         ? "a socket"
                                                     : "not a regular file";
  throw IoError(std::string("will not replace the output path: it is ") + kind + ", not an earlier output",
                {path.string()}, "name a regular file");
}

} // namespace geotandem
