// The checks a plugin-path entry passes before dlopen() (library_check.hpp).

#include "library_check.hpp"

#include <elf.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <vector>

#include "geotandem/core/error.hpp"

namespace geotandem::workflow::detail {
namespace {

const char* const fix_hint = "build or copy the library again, or remove it from the plugin path";

[[noreturn]] void refuse(const std::string& path, const std::string& why) {
  throw FormatError(why, {path}, fix_hint);
}

// What a file that is not a regular file is, for the message; empty for a regular file.
std::string kind_of(mode_t mode) {
  if (S_ISREG(mode)) return {};
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

#if defined(__x86_64__)
constexpr unsigned host_machine = EM_X86_64;
#elif defined(__aarch64__)
constexpr unsigned host_machine = EM_AARCH64;
#elif defined(__i386__)
constexpr unsigned host_machine = EM_386;
#elif defined(__arm__)
constexpr unsigned host_machine = EM_ARM;
#elif defined(__powerpc64__)
constexpr unsigned host_machine = EM_PPC64;
#elif defined(__riscv)
constexpr unsigned host_machine = EM_RISCV;
#elif defined(__s390x__)
constexpr unsigned host_machine = EM_S390;
#else
constexpr unsigned host_machine = EM_NONE; // unknown here: the machine is left to dlopen()
#endif

std::string machine_name(unsigned machine) {
  switch (machine) {
  case EM_X86_64: return "x86-64";
  case EM_AARCH64: return "AArch64";
  case EM_386: return "i386";
  case EM_ARM: return "ARM";
  case EM_PPC64: return "PowerPC64";
  case EM_RISCV: return "RISC-V";
  case EM_S390: return "s390";
  default: return "ELF machine " + std::to_string(machine);
  }
}

void read_at(int fd, void* into, std::size_t bytes, std::uint64_t offset, const std::string& path) {
  auto* out = static_cast<char*>(into);
  std::size_t done = 0;
  while (done < bytes) {
    const ssize_t n = ::pread(fd, out + done, bytes - done, static_cast<off_t>(offset + done));
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw IoError(std::string("cannot read the plugin library: ") + std::strerror(errno), {path});
    if (n == 0) refuse(path, "the file ended while its headers were read (a truncated copy?)");
    done += static_cast<std::size_t>(n);
  }
}

// `offset` + `count` * `entry` bytes within `size` bytes, without overflowing.
bool within(std::uint64_t offset, std::uint64_t count, std::uint64_t entry, std::uint64_t size) {
  if (offset > size) return false;
  return count == 0 || entry == 0 || count <= (size - offset) / entry;
}

std::string range_text(std::uint64_t offset, std::uint64_t bytes) {
  return "bytes " + std::to_string(offset) + " to " + std::to_string(offset + bytes);
}

// The ELF header, the program headers (dlopen maps the loadable segments they describe) and the
// section headers with the sections they point at, against the file's size.
template <class Ehdr, class Phdr, class Shdr> void check_elf(int fd, std::uint64_t size, const std::string& path) {
  Ehdr header{};
  read_at(fd, &header, sizeof header, 0, path);
  if (header.e_type != ET_DYN)
    refuse(path, "an ELF file of type " + std::to_string(header.e_type) + " (" +
                     (header.e_type == ET_EXEC  ? "an executable"
                      : header.e_type == ET_REL ? "an object file"
                                                : "other") +
                     "), not a shared library");
  if (host_machine != EM_NONE && header.e_machine != host_machine)
    refuse(path, "a library for " + machine_name(header.e_machine) + ", not for this machine (" +
                     machine_name(host_machine) + ")");
  const std::string ends = "the file has " + std::to_string(size) + " bytes: a truncated copy";
  if (header.e_phnum == 0 || header.e_phentsize != sizeof(Phdr))
    refuse(path, "its ELF header declares no usable program headers");
  if (!within(header.e_phoff, header.e_phnum, sizeof(Phdr), size))
    refuse(path, "its program headers (" + range_text(header.e_phoff, std::uint64_t{header.e_phnum} * sizeof(Phdr)) +
                     ") lie beyond the end of the file; " + ends);
  std::vector<Phdr> segments(header.e_phnum);
  read_at(fd, segments.data(), segments.size() * sizeof(Phdr), header.e_phoff, path);
  for (std::size_t n = 0; n < segments.size(); ++n) {
    const Phdr& s = segments[n];
    if (s.p_filesz != 0 && !within(s.p_offset, 1, s.p_filesz, size))
      refuse(path, std::string(s.p_type == PT_LOAD ? "its loadable segment " : "its segment ") + std::to_string(n) +
                       " (" + range_text(s.p_offset, s.p_filesz) + ") reaches beyond the end of the file; " + ends);
  }
  if (header.e_shoff == 0 || header.e_shnum == 0) return; // stripped of its section table: allowed
  if (header.e_shentsize != sizeof(Shdr)) refuse(path, "its ELF header declares section headers of the wrong size");
  if (!within(header.e_shoff, header.e_shnum, sizeof(Shdr), size))
    refuse(path, "its section headers (" + range_text(header.e_shoff, std::uint64_t{header.e_shnum} * sizeof(Shdr)) +
                     ") lie beyond the end of the file; " + ends);
  std::vector<Shdr> sections(header.e_shnum);
  read_at(fd, sections.data(), sections.size() * sizeof(Shdr), header.e_shoff, path);
  for (std::size_t n = 0; n < sections.size(); ++n) {
    const Shdr& s = sections[n];
    if (s.sh_type != SHT_NOBITS && s.sh_size != 0 && !within(s.sh_offset, 1, s.sh_size, size))
      refuse(path, "its section " + std::to_string(n) + " (" + range_text(s.sh_offset, s.sh_size) +
                       ") reaches beyond the end of the file; " + ends);
  }
}

// Closes the descriptor on every path out.
struct Descriptor {
  int fd;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

} // namespace

void check_plugin_library(const std::string& path) {
  // The type first, from the path alone: opening a FIFO for reading would block until a writer
  // comes, and a device may do anything when opened.
  struct stat link {};
  if (::lstat(path.c_str(), &link) != 0)
    throw IoError(std::string("cannot inspect the plugin library: ") + std::strerror(errno), {path});
  struct stat target {};
  if (::stat(path.c_str(), &target) != 0)
    throw IoError(std::string("the plugin library is a symbolic link to a file that cannot be reached: ") +
                      std::strerror(errno),
                  {path}, fix_hint);
  if (const std::string kind = kind_of(target.st_mode); !kind.empty())
    refuse(path, std::string(S_ISLNK(link.st_mode) ? "a symbolic link to " : "") + kind + ", not a shared library");

  // O_NONBLOCK: should the entry have become a FIFO since the stat, the open does not wait.
  Descriptor file{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY)};
  if (file.fd < 0)
    throw IoError(std::string("cannot read the plugin library: ") + std::strerror(errno), {path},
                  "make it readable by this user, or remove it from the plugin path");
  struct stat opened {};
  if (::fstat(file.fd, &opened) != 0 || !S_ISREG(opened.st_mode) || opened.st_ino != target.st_ino ||
      opened.st_dev != target.st_dev)
    refuse(path, "the file was replaced while it was checked");

  const auto size = static_cast<std::uint64_t>(opened.st_size);
  unsigned char ident[EI_NIDENT] = {};
  if (size < EI_NIDENT)
    refuse(path, "the file has " + std::to_string(size) +
                     " bytes, too few for an ELF header (an empty or truncated "
                     "copy, or not a library)");
  read_at(file.fd, ident, sizeof ident, 0, path);
  if (std::memcmp(ident, ELFMAG, SELFMAG) != 0) refuse(path, "not an ELF file (no \\x7fELF at its start)");
  constexpr unsigned char host_class = sizeof(void*) == 8 ? ELFCLASS64 : ELFCLASS32;
  if (ident[EI_CLASS] != host_class)
    refuse(path, std::string("a ") + (ident[EI_CLASS] == ELFCLASS32 ? "32-bit" : "64-bit") +
                     " ELF file; this process loads " + (host_class == ELFCLASS64 ? "64-bit" : "32-bit") +
                     " libraries");
  constexpr unsigned char host_order = __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__ ? ELFDATA2LSB : ELFDATA2MSB;
  if (ident[EI_DATA] != host_order) refuse(path, "an ELF file of the other byte order than this machine's");
  const std::size_t header_size = host_class == ELFCLASS64 ? sizeof(Elf64_Ehdr) : sizeof(Elf32_Ehdr);
  if (size < header_size)
    refuse(path, "the file has " + std::to_string(size) + " bytes, fewer than its ELF header (" +
                     std::to_string(header_size) + " bytes): a truncated copy");
  if constexpr (sizeof(void*) == 8)
    check_elf<Elf64_Ehdr, Elf64_Phdr, Elf64_Shdr>(file.fd, size, path);
  else
    check_elf<Elf32_Ehdr, Elf32_Phdr, Elf32_Shdr>(file.fd, size, path);
}

} // namespace geotandem::workflow::detail
