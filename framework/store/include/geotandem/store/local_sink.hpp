#pragma once
// The sink of a single-process run: writes each finished component to this process's shard and
// commits its index row, both in one place. A distributed run splits the two: workers own
// ShardWriters, the manager alone calls ComponentStore::commit.

#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <unordered_set>
#include <vector>

#include "geotandem/mesh/component.hpp"
#include "geotandem/store/shard.hpp"
#include "geotandem/store/store.hpp"

namespace geotandem::store {

struct LocalSinkOptions {
  std::string writer = "local";    // shard name
  std::optional<std::int64_t> run; // run id recorded with every component
  // Components per durable commit (one fdatasync and one index transaction per batch). A kill
  // loses at most the open batch; it is never half-committed. 1 makes every commit() durable.
  std::size_t batch_size = 32;
  // A key already stored is read back and verified; a damaged record is written again and its row
  // replaced, so that rerunning an extraction repairs what `store check` found damaged.
  bool redo_damaged = true;
};

class LocalSink final : public mesh::ComponentSink {
public:
  // `store` must be writable and outlive the sink. Opens the shard, cutting it back to the end of
  // its last indexed record (a torn tail of a killed run is dropped). Throws like ShardWriter.
  LocalSink(ComponentStore& store, LocalSinkOptions options = {});
  // Flushes what is pending; errors there are swallowed, so call close() to see them.
  ~LocalSink() override;

  // Thread-safe among callers of this sink (the store's own methods are not: while the sink is in
  // use, other threads must not call the store directly). A key already stored or pending is skipped (counted in
  // duplicates()). Throws InvalidArgument for an empty surface, IoError when writing fails.
  void commit(const mesh::Component& component) override;
  // Makes every committed component durable and indexed.
  void flush();
  // flush(), then refuses further commits.
  void close();

  std::uint64_t committed() const;
  std::uint64_t duplicates() const;
  // Components whose stored record was damaged and that were written again, and the first
  // `max_listed_keys` of their keys (a rerun names what it repaired).
  std::uint64_t redone() const;
  std::vector<std::uint64_t> redone_keys() const;
  static constexpr std::size_t max_listed_keys = 20;

private:
  void flush_locked();

  ComponentStore& store_;
  LocalSinkOptions options_;
  ShardWriter writer_;
  mutable std::mutex mutex_;
  std::vector<IndexEntry> pending_;
  std::unordered_set<std::uint64_t> pending_keys_;
  std::uint64_t committed_ = 0;
  std::uint64_t duplicates_ = 0;
  std::uint64_t redone_ = 0;
  std::vector<std::uint64_t> redone_keys_;
  bool closed_ = false;
};

} // namespace geotandem::store
