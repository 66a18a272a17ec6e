// Raw cubes: little-endian float32 in C order [inline][crossline][sample] in FILE.raw, described
// by the JSON sidecar FILE.raw.json (shape, geometry, format tag and version; see
// docs/formats-segy-raw.md). Boxes are read with one pread per contiguous run of samples, runs
// separated by small gaps being merged.

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

#include "formats.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/volume/size_guard.hpp"
#include "raw_sidecar.hpp"

namespace fs = std::filesystem;

namespace geotandem::volume::detail {
namespace {

// Samples are little-endian on disk; a big-endian host swaps them on the way in and out.
void to_or_from_little_endian(std::span<float> samples) {
  if constexpr (std::endian::native == std::endian::big) {
    for (float& value : samples) {
      auto bits = std::bit_cast<std::uint32_t>(value);
      bits = (bits >> 24) | ((bits >> 8) & 0xFF00u) | ((bits << 8) & 0xFF0000u) | (bits << 24);
      value = std::bit_cast<float>(bits);
    }
  }
}

class Descriptor {
public:
  explicit Descriptor(int fd) : fd_(fd) {}
  ~Descriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
  int get() const { return fd_; }
  // Closes and returns close()'s result, so that a writer sees a failed final flush.
  int release_and_close() {
    int result = ::close(fd_);
    fd_ = -1;
    return result;
  }

private:
  int fd_;
};

// ---- The data file -----------------------------------------------------------------------------

class RawVolume final : public Volume {
public:
  RawVolume(std::string path, Geometry geometry, int fd)
      : path_(std::move(path)), geometry_(std::move(geometry)), fd_(fd) {}

  const Geometry& geometry() const override { return geometry_; }
  std::string format() const override { return "raw"; }
  std::string source() const override { return path_; }

protected:
  // One run per trace of the box (its samples lo..hi), in file order, which is also the order of
  // `out`. Runs that touch are read by one pread straight into `out`; runs separated by small
  // gaps are read by one pread into a scratch buffer and copied out, because a system call costs
  // about as much as copying tens of kilobytes from the page cache (64^3 blocks read ~10x faster).
  void read_box(const Box& box, std::span<float> out) const override {
    const auto run_bytes = static_cast<std::uint64_t>(box.size(2)) * sizeof(float);
    auto* dst = reinterpret_cast<char*>(out.data());
    std::vector<char> scratch;
    Group group;
    for (std::int64_t i = box.lo[0]; i < box.hi[0]; ++i)
      for (std::int64_t j = box.lo[1]; j < box.hi[1]; ++j, dst += run_bytes) {
        const std::uint64_t offset = geometry_.bounds().offset({i, j, box.lo[2]}) * sizeof(float);
        if (!group.runs.empty() && !group.accepts(offset, run_bytes)) read_group(group, scratch, box);
        group.add(offset, run_bytes, dst);
      }
    read_group(group, scratch, box);
    to_or_from_little_endian(out);
  }

private:
  static constexpr std::uint64_t kMaxGap = std::uint64_t{64} * 1024;        // bytes skipped between two runs
  static constexpr std::uint64_t kMaxSpan = std::uint64_t{8} * 1024 * 1024; // bytes of one scratch read

  struct Run {
    std::uint64_t offset;
    char* dst;
  };
  struct Group {
    std::vector<Run> runs;
    std::uint64_t end = 0, run_bytes = 0;
    bool contiguous = true;

    bool accepts(std::uint64_t offset, std::uint64_t bytes) const {
      if (offset == end && contiguous) return true; // straight into `out`, no size limit
      return offset - end <= kMaxGap && offset + bytes - runs.front().offset <= kMaxSpan;
    }
    void add(std::uint64_t offset, std::uint64_t bytes, char* dst) {
      contiguous = runs.empty() || (contiguous && offset == end);
      runs.push_back({offset, dst});
      end = offset + bytes;
      run_bytes = bytes;
    }
  };

  void read_group(Group& group, std::vector<char>& scratch, const Box& box) const {
    const std::uint64_t start = group.runs.front().offset, span = group.end - start;
    if (group.contiguous) {
      read_bytes(start, span, group.runs.front().dst, box);
    } else {
      scratch.resize(span);
      read_bytes(start, span, scratch.data(), box);
      for (const Run& run : group.runs)
        std::memcpy(run.dst, scratch.data() + (run.offset - start), group.run_bytes);
    }
    group = Group{};
  }

  void read_bytes(std::uint64_t offset, std::uint64_t count, char* dst, const Box& box) const {
    while (count > 0) {
      ssize_t got = ::pread(fd_.get(), dst, count, static_cast<off_t>(offset));
      if (got < 0 && errno == EINTR) continue;
      if (got < 0)
        throw IoError(std::string("read failed: ") + std::strerror(errno), {path_, {}, {}, "box " + box.to_string()});
      if (got == 0)
        throw FormatError("unexpected end of file at byte " + std::to_string(offset), {path_},
                          "the file shrank after it was opened; copy it again");
      dst += got;
      offset += static_cast<std::uint64_t>(got);
      count -= static_cast<std::uint64_t>(got);
    }
  }

  std::string path_;
  Geometry geometry_;
  Descriptor fd_;
};

void write_all_at(int fd, const float* data, std::size_t count, std::uint64_t offset, const std::string& path) {
  const auto* bytes = reinterpret_cast<const char*>(data);
  std::size_t left = count * sizeof(float);
  while (left > 0) {
    ssize_t put = ::pwrite(fd, bytes, left, static_cast<off_t>(offset));
    if (put < 0 && errno == EINTR) continue;
    if (put < 0) throw IoError(std::string("write failed: ") + std::strerror(errno), {path}, "check the free space");
    bytes += put;
    offset += static_cast<std::uint64_t>(put);
    left -= static_cast<std::size_t>(put);
  }
}

void write_all(int fd, const float* data, std::size_t count, const std::string& path) {
  const auto* bytes = reinterpret_cast<const char*>(data);
  std::size_t left = count * sizeof(float);
  while (left > 0) {
    ssize_t put = ::write(fd, bytes, left);
    if (put < 0 && errno == EINTR) continue;
    if (put < 0) throw IoError(std::string("write failed: ") + std::strerror(errno), {path}, "check the free space");
    bytes += put;
    left -= static_cast<std::size_t>(put);
  }
}

} // namespace

std::unique_ptr<Volume> open_raw(const std::string& path, const OpenOptions&) {
  const std::string sidecar = raw_sidecar_of(path);
  Geometry g = read_raw_sidecar(sidecar);
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) throw IoError("cannot get the size of the raw data file: " + ec.message(), {path});
  const auto counted = checked_byte_count(g.shape, sizeof(float));
  if (!counted)
    throw FormatError("the shape " + g.bounds().to_string() + " in " + sidecar +
                          " needs more than 2^64 bytes of float32; the raw data file has " + std::to_string(size) +
                          " bytes",
                      {sidecar}, "check the shape in the sidecar");
  const std::uintmax_t wanted = *counted;
  if (size != wanted)
    throw FormatError("the raw data file has " + std::to_string(size) + " bytes but the shape " +
                          g.bounds().to_string() + " in " + sidecar + " needs " + std::to_string(wanted) +
                          " bytes of float32",
                      {path}, "check the shape in the sidecar, or copy the data file again if it is truncated");
  int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw IoError(std::string("cannot open the raw data file: ") + std::strerror(errno), {path});
  return std::make_unique<RawVolume>(path, std::move(g), fd);
}

void write_raw(const Volume& volume, const std::string& path, const WriteOptions&, Progress& progress,
               const CancelToken& cancel) {
  write_raw_slabs(volume, path, 0, 1, "writing raw " + path, progress, cancel);
}

void write_raw_slabs(const Volume& volume, const std::string& path, int axis, std::int64_t thickness,
                     const std::string& task, Progress& progress, const CancelToken& cancel) {
  if (axis < 0 || axis > 2) throw InvalidArgument("raw slabs go along axis 0, 1 or 2, not " + std::to_string(axis));
  const Geometry& g = volume.geometry();
  g.validate();
  const std::string sidecar = raw_sidecar_of(path), partial = sidecar + ".partial";
  Descriptor fd(::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644));
  if (fd.get() < 0)
    throw IoError(std::string("cannot create the raw data file: ") + std::strerror(errno), {path},
                  "check that the directory exists and is writable");
  try {
    const std::int64_t ni = g.shape[0], nj = g.shape[1], nk = g.shape[2];
    const std::int64_t along = g.shape[axis], t = std::clamp<std::int64_t>(thickness, 1, along);
    const std::int64_t slabs = (along + t - 1) / t;
    std::vector<float> slab;
    const char* units[3] = {"inline slabs", "crossline slabs", "sample slabs"};
    progress.begin(task, static_cast<std::uint64_t>(slabs), units[axis]);
    for (std::int64_t s = 0; s < slabs; ++s) {
      cancel.throw_if_cancelled();
      const std::int64_t lo = s * t, hi = std::min(along, lo + t);
      Box box{{0, 0, 0}, {ni, nj, nk}};
      box.lo[axis] = lo;
      box.hi[axis] = hi;
      slab.resize(static_cast<std::size_t>(box.count()));
      volume.read(box, slab);
      to_or_from_little_endian(slab);
      if (axis == 0) {
        write_all(fd.get(), slab.data(), slab.size(), path); // the slabs follow one another in the file
      } else if (axis == 1) {
        // Each inline's part of the slab is one run of the file.
        const auto run = static_cast<std::size_t>((hi - lo) * nk);
        for (std::int64_t i = 0; i < ni; ++i)
          write_all_at(fd.get(), slab.data() + static_cast<std::size_t>(i) * run, run,
                       static_cast<std::uint64_t>((i * nj + lo) * nk) * sizeof(float), path);
      } else {
        // Each trace's part of the slab is one run of the file.
        const auto run = static_cast<std::size_t>(hi - lo);
        for (std::int64_t trace = 0; trace < ni * nj; ++trace)
          write_all_at(fd.get(), slab.data() + static_cast<std::size_t>(trace) * run, run,
                       static_cast<std::uint64_t>(trace * nk + lo) * sizeof(float), path);
      }
      progress.update(static_cast<std::uint64_t>(s + 1));
    }
    if (fd.release_and_close() != 0)
      throw IoError(std::string("write failed on close: ") + std::strerror(errno), {path}, "check the free space");
    // The sidecar comes last and appears whole (rename), so that a raw cube that can be detected
    // is a complete one.
    {
      std::ofstream out(partial, std::ios::binary | std::ios::trunc);
      out << raw_sidecar_text(g);
      out.close();
      if (!out) throw IoError("cannot write the raw sidecar", {partial}, "check the free space");
    }
    std::error_code renamed;
    fs::rename(partial, sidecar, renamed);
    if (renamed) throw IoError("cannot put the raw sidecar in place: " + renamed.message(), {sidecar});
    progress.end();
  } catch (...) {
    std::error_code ec;
    fs::remove(path, ec);
    fs::remove(partial, ec);
    throw;
  }
}

} // namespace geotandem::volume::detail
