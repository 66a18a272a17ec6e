// The manager's relay of partial surfaces (surface_relay.hpp).
#include "surface_relay.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <system_error>

#include "geotandem/core/error.hpp"

namespace geotandem::runtime::detail {
namespace {

constexpr const char* kSpillPrefix = "transfer-";
constexpr const char* kSpillSuffix = ".surface";

bool is_spill_file(const std::filesystem::path& p) {
  const std::string name = p.filename().string();
  return name.starts_with(kSpillPrefix) && name.ends_with(kSpillSuffix);
}

// Removes the relay's files in `dir`, then `dir` when that leaves it empty; errors are ignored
// (a directory that cannot be listed holds none of ours that could be removed either).
void remove_spill_files(const std::filesystem::path& dir) noexcept {
  std::error_code ec;
  if (dir.empty() || !std::filesystem::is_directory(dir, ec)) return;
  for (std::filesystem::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    if (is_spill_file(it->path())) std::filesystem::remove(it->path(), ec);
  std::filesystem::remove(dir, ec); // only when empty
}

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};

} // namespace

SurfaceRelay::SurfaceRelay(std::uint64_t max_surface, std::size_t chunk_bytes, std::uint64_t memory,
                           std::filesystem::path spill_dir)
    : max_surface_(max_surface), chunk_bytes_(chunk_bytes), memory_(memory), spill_dir_(std::move(spill_dir)) {
  remove_spill_files(spill_dir_); // left by a manager that was killed
}

SurfaceRelay::~SurfaceRelay() {
  close();
}

void SurfaceRelay::close() noexcept {
  inbound_.clear();
  outbound_.clear();
  whole_.clear();
  kept_.clear();
  usage_.held = 0;
  remove_spill_files(spill_dir_);
}

void SurfaceRelay::begin_inbound(const std::string& token) {
  inbound_.insert_or_assign(token, SurfaceAssembler(max_surface_, std::nullopt, chunk_bytes_));
}

std::optional<std::string> SurfaceRelay::chunk_in(const std::string& token, std::uint64_t offset,
                                                  std::span<const std::byte> bytes, std::uint64_t size_hint) {
  auto it = inbound_.find(token);
  if (it == inbound_.end()) return "a chunk outside a SEND";
  if (offset == 0) it->second.reserve_hint(size_hint);
  return it->second.add(offset, bytes);
}

std::optional<std::string> SurfaceRelay::end_inbound(const std::string& token, std::uint64_t total,
                                                     std::uint64_t checksum, std::uint64_t& bytes) {
  auto it = inbound_.find(token);
  if (it == inbound_.end()) return "the end of a SEND that did not start";
  SurfaceAssembler in = std::move(it->second);
  inbound_.erase(it);
  bytes = in.size();
  if (std::optional<std::string> why = in.finish(total, checksum)) return why;
  whole_.insert_or_assign(token, Parcel{in.take(), checksum, bytes, {}});
  return std::nullopt;
}

std::optional<std::string> SurfaceRelay::keep(const std::string& token, TransferId transfer) {
  auto it = whole_.find(token);
  if (it == whole_.end()) return std::nullopt;
  Parcel parcel = std::move(it->second);
  whole_.erase(it);
  std::optional<std::string> warning;
  if (usage_.held + parcel.size > memory_ && !spill_dir_.empty() && !spill_failed_) warning = spill(transfer, parcel);
  if (parcel.file.empty()) {
    usage_.held += parcel.size;
    usage_.peak_held = std::max(usage_.peak_held, usage_.held);
  }
  if (auto old = kept_.find(transfer); old != kept_.end()) release(old->second);
  kept_.insert_or_assign(transfer, std::move(parcel));
  return warning;
}

std::optional<std::string> SurfaceRelay::spill(TransferId transfer, Parcel& parcel) {
  const std::filesystem::path file = spill_dir_ / (kSpillPrefix + std::to_string(transfer) + kSpillSuffix);
  std::string why;
  std::error_code ec;
  std::filesystem::create_directories(spill_dir_, ec);
  if (ec) {
    why = "cannot create " + spill_dir_.string() + ": " + ec.message();
  } else if (std::unique_ptr<std::FILE, FileCloser> f{std::fopen(file.c_str(), "wb")}; !f) {
    why = "cannot create " + file.string() + ": " + std::strerror(errno);
  } else {
    const bool written = std::fwrite(parcel.bytes.data(), 1, parcel.bytes.size(), f.get()) == parcel.bytes.size();
    const int saved = errno;
    if (!written || std::fclose(f.release()) != 0)
      why = "cannot write " + file.string() + ": " + std::strerror(written ? errno : saved);
  }
  if (!why.empty()) {
    std::filesystem::remove(file, ec);
    spill_failed_ = true;
    return "the partial surfaces waiting for their merge stay in memory past the relay's budget of " +
           std::to_string(memory_ >> 20) + " MiB: " + why;
  }
  std::vector<std::byte>().swap(parcel.bytes);
  parcel.file = file;
  ++usage_.spilled;
  usage_.spilled_bytes += parcel.size;
  return std::nullopt;
}

void SurfaceRelay::load(Parcel& parcel) const {
  const std::string hint =
      "the partial surface waited there for its merge; a rerun of the same command resumes from the finished blocks";
  std::unique_ptr<std::FILE, FileCloser> f{std::fopen(parcel.file.c_str(), "rb")};
  if (!f)
    throw IoError(std::string("cannot open a waiting partial surface: ") + std::strerror(errno),
                  {.file = parcel.file.string()}, hint);
  parcel.bytes.resize(parcel.size);
  const std::size_t got = std::fread(parcel.bytes.data(), 1, parcel.bytes.size(), f.get());
  if (got != parcel.size || std::fgetc(f.get()) != EOF)
    throw IoError("a waiting partial surface is not the " + std::to_string(parcel.size) + " bytes written",
                  {.file = parcel.file.string()}, hint);
  if (surface_checksum(parcel.bytes) != parcel.checksum)
    throw IoError("a waiting partial surface changed on disk (its checksum does not match)",
                  {.file = parcel.file.string()}, hint);
  std::error_code ec;
  std::filesystem::remove(parcel.file, ec);
  parcel.file.clear();
}

void SurfaceRelay::release(Parcel& parcel) {
  if (parcel.file.empty()) {
    usage_.held -= std::min(usage_.held, parcel.size);
  } else {
    std::error_code ec;
    std::filesystem::remove(parcel.file, ec);
  }
}

SurfaceRelay::Header SurfaceRelay::begin_outbound(const std::string& token, TransferId transfer) {
  Outbound out;
  auto kept = kept_.find(transfer);
  if (kept == kept_.end())
    throw std::logic_error("surface relay: no surface kept for transfer " + std::to_string(transfer));
  out.parcel = std::move(kept->second);
  kept_.erase(kept);
  if (out.parcel.file.empty()) {
    release(out.parcel); // leaves the bytes: only what is held is counted down
  } else {
    load(out.parcel);
  }
  const Header h{out.parcel.bytes.size(), out.parcel.checksum};
  outbound_.insert_or_assign(token, std::move(out));
  return h;
}

void SurfaceRelay::pump(const std::string& token, std::uint64_t credits,
                        const std::function<void(std::uint64_t, std::span<const std::byte>)>& send) {
  auto it = outbound_.find(token);
  if (it == outbound_.end()) return;
  Outbound& out = it->second;
  out.ahead -= std::min(out.ahead, credits);
  const std::span<const std::byte> all(out.parcel.bytes);
  while (out.ahead < kChunkWindow && out.offset < all.size()) {
    const std::size_t n = std::min<std::size_t>(chunk_bytes_, all.size() - out.offset);
    send(out.offset, all.subspan(out.offset, n));
    out.offset += n;
    ++out.ahead;
  }
  if (out.offset >= all.size()) outbound_.erase(it); // every chunk is on its way
}

void SurfaceRelay::forget(const std::string& token) {
  inbound_.erase(token);
  outbound_.erase(token);
  whole_.erase(token);
}

void SurfaceRelay::drop_kept(const std::function<bool(TransferId)>& gone) {
  for (auto it = kept_.begin(); it != kept_.end();) {
    if (!gone(it->first)) {
      ++it;
      continue;
    }
    release(it->second);
    it = kept_.erase(it);
  }
}

} // namespace geotandem::runtime::detail
