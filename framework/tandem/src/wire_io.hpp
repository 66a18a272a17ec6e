#pragma once
// Byte streams of the working-surface wire form (surface_wire.cpp): fixed-size little-endian
// fields without padding, and a reader that refuses to run past the payload or to believe a count
// the payload cannot hold.

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include "geotandem/core/error.hpp"
#include "working_mesh.hpp"

namespace geotandem::tandem::detail {

class Writer {
public:
  template <class T> void put(T v) {
    static_assert(std::is_arithmetic_v<T>);
    const auto at = out_.size();
    out_.resize(at + sizeof(T));
    std::memcpy(out_.data() + at, &v, sizeof(T));
  }
  void put(const Vec3& v) {
    for (double x : v)
      put(x);
  }
  void count(std::size_t n) { put(static_cast<std::uint64_t>(n)); }
  std::vector<std::byte>& bytes() { return out_; }

private:
  std::vector<std::byte> out_;
};

class Reader {
public:
  explicit Reader(std::span<const std::byte> in) : in_(in) {}
  template <class T> T get() {
    static_assert(std::is_arithmetic_v<T>);
    need(sizeof(T));
    T v;
    std::memcpy(&v, in_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return v;
  }
  Vec3 vec() {
    Vec3 v;
    for (double& x : v)
      x = get<double>();
    return v;
  }
  // A count of items of at least `item_size` bytes each: refused when the rest cannot hold them
  // (so a corrupt count never makes us allocate wildly).
  std::size_t count(std::size_t item_size, const char* what) {
    const auto n = get<std::uint64_t>();
    if (item_size > 0 && n > (in_.size() - at_) / item_size)
      throw DataError(std::string("working-surface record: the count of ") + what + " (" + std::to_string(n) +
                      ") does not fit in the payload");
    return static_cast<std::size_t>(n);
  }
  bool done() const { return at_ == in_.size(); }
  std::size_t offset() const { return at_; }

private:
  void need(std::size_t n) const {
    if (in_.size() - at_ < n)
      throw DataError("working-surface record: the payload ends at byte " + std::to_string(in_.size()) +
                      " in the middle of a field");
  }
  std::span<const std::byte> in_;
  std::size_t at_ = 0;
};

} // namespace geotandem::tandem::detail
