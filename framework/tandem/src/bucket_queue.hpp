#pragma once
// W, the edges delayed by the front, as buckets of unit width over their lag key (reach, or the
// coordinate along the axis). activate(k) releases every edge whose key is below k; with buckets
// that is whole buckets below floor(k) plus a check of one bucket, and pushes and removals are
// O(1) instead of a heap's O(log n). Keys are >= 0 (index coordinates); larger keys than the cap
// share the last bucket, which is scanned.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace geotandem::tandem::detail {

class BucketQueue {
public:
  // `slots` maps item -> position inside its bucket (shared with the other queues).
  explicit BucketQueue(std::vector<std::int32_t>* slots) : slots_(slots) {}

  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }

  void push(std::int32_t item, double key) {
    const std::size_t b = bucket_of(key);
    if (b >= buckets_.size()) buckets_.resize(b + 1);
    (*slots_)[static_cast<std::size_t>(item)] = static_cast<std::int32_t>(buckets_[b].size());
    buckets_[b].push_back(item);
    lowest_ = std::min(lowest_, b);
    ++size_;
  }
  // `key` must be the key the item was pushed with.
  void erase(std::int32_t item, double key) {
    std::vector<std::int32_t>& bucket = buckets_[bucket_of(key)];
    const std::int32_t slot = (*slots_)[static_cast<std::size_t>(item)];
    const std::int32_t last = bucket.back();
    bucket[static_cast<std::size_t>(slot)] = last;
    (*slots_)[static_cast<std::size_t>(last)] = slot;
    bucket.pop_back();
    (*slots_)[static_cast<std::size_t>(item)] = -1;
    --size_;
  }
  // Appends to `out` every item of the lowest non-empty bucket if it may hold keys below `front`
  // (the caller checks each key); returns false when no bucket can.
  bool lowest_below(double front, std::vector<std::int32_t>& out) {
    while (lowest_ < buckets_.size() && buckets_[lowest_].empty()) {
      // Behind the front: it will rarely fill again, so its storage goes back.
      std::vector<std::int32_t>().swap(buckets_[lowest_]);
      ++lowest_;
    }
    if (lowest_ >= buckets_.size() || !(static_cast<double>(lowest_) < front)) return false;
    out.assign(buckets_[lowest_].begin(), buckets_[lowest_].end());
    return true;
  }
  // Forgets every item without touching the slots (they are being renumbered), and gives the
  // storage back.
  void clear() {
    std::vector<std::vector<std::int32_t>>().swap(buckets_);
    size_ = 0;
    lowest_ = 0;
  }

private:
  static constexpr std::size_t kCap = std::size_t{1} << 17;
  static std::size_t bucket_of(double key) {
    if (!(key > 0.0)) return 0;
    if (!(key < static_cast<double>(kCap))) return kCap;
    return static_cast<std::size_t>(key);
  }

  std::vector<std::vector<std::int32_t>> buckets_;
  std::vector<std::int32_t>* slots_;
  std::size_t lowest_ = 0;
  std::size_t size_ = 0;
};

} // namespace geotandem::tandem::detail
