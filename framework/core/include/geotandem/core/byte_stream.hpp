#pragma once
// Fixed-size fields in the host's byte order (little-endian on every machine geotandem builds for)
// without padding, for the wire forms of messages and surfaces. The reader refuses to run past its
// span and to believe a length or a count the span cannot hold, so a damaged or hostile payload
// is an error of the caller's type, never an overrun or a wild allocation.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace geotandem {

class ByteWriter {
public:
  template <class T> void put(T v) {
    static_assert(std::is_arithmetic_v<T>);
    const auto at = out_.size();
    out_.resize(at + sizeof(T));
    std::memcpy(out_.data() + at, &v, sizeof(T));
  }
  void count(std::size_t n) { put(static_cast<std::uint64_t>(n)); }
  // Room for n bytes in all, when the size is known in advance (a growing array doubles).
  void reserve(std::size_t n) { out_.reserve(n); }
  // A length, then the bytes.
  void put_bytes(std::span<const std::byte> b) {
    count(b.size());
    out_.insert(out_.end(), b.begin(), b.end());
  }
  void put_text(const std::string& s) { put_bytes(std::as_bytes(std::span(s.data(), s.size()))); }
  std::vector<std::byte>& bytes() { return out_; }

private:
  std::vector<std::byte> out_;
};

// Throws Error (constructible from a message) naming `record` ("message", "working-surface
// record") when the payload is too short or a count cannot fit.
template <class Error> class ByteReader {
public:
  ByteReader(std::span<const std::byte> in, std::string record) : in_(in), record_(std::move(record)) {}

  template <class T> T get(const char* what = "a field") {
    static_assert(std::is_arithmetic_v<T>);
    need(sizeof(T), what);
    T v;
    std::memcpy(&v, in_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return v;
  }
  std::span<const std::byte> get_bytes(const char* what) {
    const auto n = get<std::uint64_t>(what);
    need(n, what);
    const auto out = in_.subspan(at_, static_cast<std::size_t>(n));
    at_ += static_cast<std::size_t>(n);
    return out;
  }
  std::string get_text(const char* what) {
    const auto b = get_bytes(what);
    return std::string(reinterpret_cast<const char*>(b.data()), b.size());
  }
  // A count of items of at least `item_size` bytes each, refused when the rest cannot hold them.
  std::size_t count(std::size_t item_size, const char* what) {
    const auto n = get<std::uint64_t>(what);
    if (item_size > 0 && n > (in_.size() - at_) / item_size)
      throw Error(record_ + ": the count of " + what + " (" + std::to_string(n) + ") does not fit in the payload");
    return static_cast<std::size_t>(n);
  }
  bool done() const { return at_ == in_.size(); }
  std::size_t offset() const { return at_; }

private:
  void need(std::uint64_t n, const char* what) const {
    if (in_.size() - at_ < n)
      throw Error(record_ + ": the payload ends in the middle of " + what + " (truncated at byte " +
                  std::to_string(in_.size()) + ")");
  }
  std::span<const std::byte> in_;
  std::string record_;
  std::size_t at_ = 0;
};

} // namespace geotandem
