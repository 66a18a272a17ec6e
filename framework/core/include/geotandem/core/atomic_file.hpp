#pragma once
// A file that appears whole or not at all: written under a unique temporary name beside its target
// (".NAME.XXXXXX.tmp", made with O_EXCL, so two writers of one target never share it), made
// durable (fsync) and renamed over the target. A fixed temporary name (NAME.part) let two
// processes exporting to one path interleave in it and leave the header of one export with the
// body of the other. The temporary is removed when the file is dropped before commit() (an error,
// a cancel), so no half-written file is left behind.

#include <filesystem>
#include <fstream>
#include <string>

namespace geotandem {

class AtomicFile {
public:
  // Creates the temporary in the target's directory (which must exist). Throws IoError naming the
  // directory when it cannot be created.
  explicit AtomicFile(std::filesystem::path target, std::ios::openmode mode = std::ios::binary);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::ostream& stream() { return out_; }
  const std::filesystem::path& temporary() const { return temporary_; }
  const std::filesystem::path& target() const { return target_; }
  // Flushes, syncs and renames the temporary over the target, then syncs the directory. Throws
  // IoError (the temporary removed) when any of it fails; `what` names the file for the message
  // ("the export file", "the report").
  void commit(const std::string& what = "the file");

private:
  std::filesystem::path target_, temporary_;
  std::ofstream out_;
  bool committed_ = false;
};

// Writes `text` to `path` through an AtomicFile.
void write_file_atomically(const std::filesystem::path& path, const std::string& text,
                           const std::string& what = "the file");

} // namespace geotandem
