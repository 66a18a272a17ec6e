#pragma once
// Little-endian fields without padding for the runtime's messages; the reader refuses to run past
// its span and to believe a length the span cannot hold.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include "geotandem/runtime/protocol.hpp"

namespace geotandem::runtime::detail {

class ByteWriter {
public:
  template <class T> void put(T v) {
    static_assert(std::is_arithmetic_v<T>);
    const auto at = out_.size();
    out_.resize(at + sizeof(T));
    std::memcpy(out_.data() + at, &v, sizeof(T));
  }
  void put_bytes(std::span<const std::byte> b) {
    put(static_cast<std::uint64_t>(b.size()));
    out_.insert(out_.end(), b.begin(), b.end());
  }
  void put_text(const std::string& s) { put_bytes(std::as_bytes(std::span(s.data(), s.size()))); }
  std::vector<std::byte>& bytes() { return out_; }

private:
  std::vector<std::byte> out_;
};

class ByteReader {
public:
  explicit ByteReader(std::span<const std::byte> in) : in_(in) {}
  template <class T> T get() {
    static_assert(std::is_arithmetic_v<T>);
    need(sizeof(T), "a field");
    T v;
    std::memcpy(&v, in_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return v;
  }
  std::span<const std::byte> get_bytes(const char* what) {
    const auto n = get<std::uint64_t>();
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
    const auto n = get<std::uint64_t>();
    if (n > (in_.size() - at_) / item_size)
      throw ProtocolError(std::string("message: the count of ") + what + " (" + std::to_string(n) +
                          ") does not fit in the payload");
    return static_cast<std::size_t>(n);
  }
  bool done() const { return at_ == in_.size(); }

private:
  void need(std::uint64_t n, const char* what) const {
    if (in_.size() - at_ < n)
      throw ProtocolError(std::string("message: the payload ends in the middle of ") + what + " (truncated)");
  }
  std::span<const std::byte> in_;
  std::size_t at_ = 0;
};

} // namespace geotandem::runtime::detail
