#pragma once
// The worker's sink for finished components (worker.cpp).
#include <chrono>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

#include "geotandem/mesh/component.hpp"
#include "geotandem/store/shard.hpp"
#include "geotandem/store/store.hpp"

namespace geotandem::runtime::detail {

// Finished components to the worker's shard; their index entries wait for the next COMMIT, which
// goes at the end of the task or, during a long one, every 200 ms (or 256 components): a manager
// killed mid-task then loses little.
class ShardSink final : public mesh::ComponentSink {
public:
  ShardSink(store::ShardWriter& writer, std::int64_t run, std::function<void()> flush)
      : writer_(writer), run_(run), flush_(std::move(flush)) {}
  void commit(const mesh::Component& c) override {
    store::IndexEntry e;
    e.key = c.key;
    e.location = writer_.append(c);
    e.stats = c.stats;
    e.run = run_;
    pending_.push_back(std::move(e));
    if (pending_.size() >= 256 || std::chrono::steady_clock::now() - last_ > std::chrono::milliseconds(200)) flush_();
  }
  std::vector<store::IndexEntry> take() {
    last_ = std::chrono::steady_clock::now();
    if (!pending_.empty()) writer_.sync();
    return std::exchange(pending_, {});
  }

private:
  store::ShardWriter& writer_;
  std::int64_t run_;
  std::function<void()> flush_;
  std::vector<store::IndexEntry> pending_;
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

} // namespace geotandem::runtime::detail
