#pragma once
// Lattice-edge id -> vertex index, for the vertices a coming layer may repeat. Open addressing with
// linear probing: a layer inserts and looks up hundreds of thousands of ids, and std::unordered_map
// allocates per node.

#include <algorithm>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace geotandem::tandem::detail {

inline constexpr std::uint64_t kNoLatticeId = std::numeric_limits<std::uint64_t>::max();

class IdMap {
public:
  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }

  // The value stored for `id`, or -1.
  std::int32_t find(std::uint64_t id) const {
    if (keys_.empty()) return -1;
    for (std::size_t i = bucket(id);; i = (i + 1) & mask_) {
      if (keys_[i] == id) return values_[i];
      if (keys_[i] == kNoLatticeId) return -1;
    }
  }
  // Inserts or overwrites. `id` must not be kNoLatticeId.
  void insert(std::uint64_t id, std::int32_t value) {
    if ((size_ + 1) * 2 > keys_.size()) grow();
    for (std::size_t i = bucket(id);; i = (i + 1) & mask_) {
      if (keys_[i] == id) {
        values_[i] = value;
        return;
      }
      if (keys_[i] == kNoLatticeId) {
        keys_[i] = id;
        values_[i] = value;
        ++size_;
        return;
      }
    }
  }
  // Keeps the capacity (the next layer has a similar size).
  void clear() {
    if (size_ == 0) return;
    std::fill(keys_.begin(), keys_.end(), kNoLatticeId);
    size_ = 0;
  }
  void swap(IdMap& other) noexcept {
    keys_.swap(other.keys_);
    values_.swap(other.values_);
    std::swap(size_, other.size_);
    std::swap(mask_, other.mask_);
    std::swap(shift_, other.shift_);
  }
  // Calls f(id, value&) for every entry; f may change the value (remapping after a compaction).
  template <class F> void for_each(F&& f) {
    for (std::size_t i = 0; i < keys_.size(); ++i)
      if (keys_[i] != kNoLatticeId) f(keys_[i], values_[i]);
  }
  template <class F> void for_each(F&& f) const {
    for (std::size_t i = 0; i < keys_.size(); ++i)
      if (keys_[i] != kNoLatticeId) f(keys_[i], values_[i]);
  }

private:
  std::size_t bucket(std::uint64_t id) const {
    // Fibonacci hashing: lattice ids are dense and strided by 3, so spread them.
    return static_cast<std::size_t>((id * 0x9E3779B97F4A7C15ull) >> shift_);
  }
  void grow() {
    std::vector<std::uint64_t> old_keys = std::move(keys_);
    std::vector<std::int32_t> old_values = std::move(values_);
    const std::size_t capacity = old_keys.empty() ? 1024 : old_keys.size() * 2;
    keys_.assign(capacity, kNoLatticeId);
    values_.assign(capacity, -1);
    mask_ = capacity - 1;
    shift_ = 64;
    for (std::size_t c = capacity; c > 1; c >>= 1)
      --shift_;
    size_ = 0;
    for (std::size_t i = 0; i < old_keys.size(); ++i)
      if (old_keys[i] != kNoLatticeId) insert(old_keys[i], old_values[i]);
  }

  std::vector<std::uint64_t> keys_;
  std::vector<std::int32_t> values_;
  std::size_t size_ = 0;
  std::size_t mask_ = 0;
  int shift_ = 64;
};

} // namespace geotandem::tandem::detail
