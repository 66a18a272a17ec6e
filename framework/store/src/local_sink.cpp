#include "geotandem/store/local_sink.hpp"

#include "geotandem/core/error.hpp"
#include "geotandem/store/check.hpp"

namespace geotandem::store {

namespace {

ShardWriter open_writer(ComponentStore& store, const LocalSinkOptions& options) {
  if (!store.writable())
    throw InvalidArgument("a local sink needs a store open for writing", {store.directory().string()});
  ShardWriterOptions writer_options;
  // This process is the index's only writer: whatever follows the last indexed record of its
  // shard is a torn or never-indexed tail of an earlier, killed run.
  writer_options.valid_end = store.indexed_end(options.writer);
  // A shard cut short under the index (a damaged store): keep what is there; the rows that point
  // past its end are damaged records, which the rerun writes again (see commit).
  std::error_code ec;
  auto size = std::filesystem::file_size(shard_path(store.directory(), options.writer), ec);
  if (!ec && size < *writer_options.valid_end) writer_options.valid_end = size;
  return ShardWriter(store.directory(), options.writer, store.geometry(), writer_options);
}

} // namespace

LocalSink::LocalSink(ComponentStore& store, LocalSinkOptions options)
    : store_(store), options_(std::move(options)), writer_(open_writer(store, options_)) {
  if (options_.batch_size == 0) options_.batch_size = 1;
}

LocalSink::~LocalSink() {
  try {
    std::lock_guard lock(mutex_);
    if (!closed_) flush_locked();
  } catch (...) {
    // Destructors must not throw; close() reports the same error to callers who ask.
  }
}

void LocalSink::commit(const mesh::Component& component) {
  std::lock_guard lock(mutex_);
  if (closed_) throw InvalidArgument("commit to a closed local sink", {store_.directory().string()});
  bool replace = false;
  if (pending_keys_.count(component.key)) {
    ++duplicates_;
    return;
  }
  if (auto row = store_.find(component.key)) {
    if (!options_.redo_damaged || !verify_component(store_, *row)) {
      ++duplicates_;
      return;
    }
    replace = true;
    ++redone_;
    if (redone_keys_.size() < max_listed_keys) redone_keys_.push_back(component.key);
  }
  IndexEntry entry;
  entry.replace = replace;
  entry.key = component.key;
  entry.location = writer_.append(component);
  entry.stats = component.stats;
  entry.run = options_.run;
  pending_.push_back(std::move(entry));
  pending_keys_.insert(component.key);
  if (pending_.size() >= options_.batch_size) flush_locked();
}

void LocalSink::flush() {
  std::lock_guard lock(mutex_);
  flush_locked();
}

void LocalSink::close() {
  std::lock_guard lock(mutex_);
  if (closed_) return;
  flush_locked();
  closed_ = true;
}

void LocalSink::flush_locked() {
  if (pending_.empty()) return;
  // The records must be on disk before the index points at them.
  writer_.sync();
  committed_ += store_.commit(pending_);
  pending_.clear();
  pending_keys_.clear();
}

std::uint64_t LocalSink::committed() const {
  std::lock_guard lock(mutex_);
  return committed_;
}

std::uint64_t LocalSink::redone() const {
  std::lock_guard lock(mutex_);
  return redone_;
}

std::vector<std::uint64_t> LocalSink::redone_keys() const {
  std::lock_guard lock(mutex_);
  return redone_keys_;
}

std::uint64_t LocalSink::duplicates() const {
  std::lock_guard lock(mutex_);
  return duplicates_;
}

} // namespace geotandem::store
