// The manager's index writes on their own thread (commit_queue.hpp).
#include "commit_queue.hpp"

#include <ctime>

#include <iterator>
#include <utility>

namespace geotandem::runtime::detail {

CommitQueue::CommitQueue(ComponentCommitter& committer) : committer_(committer), thread_([this] { loop(); }) {}

CommitQueue::~CommitQueue() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void CommitQueue::commit(std::vector<store::IndexEntry> entries) {
  {
    std::lock_guard lock(mutex_);
    queue_.emplace_back(std::move(entries));
  }
  wake_.notify_one();
}

void CommitQueue::then(std::function<void()> action) {
  {
    std::lock_guard lock(mutex_);
    queue_.emplace_back(std::move(action));
  }
  wake_.notify_one();
}

void CommitQueue::rethrow_failure() {
  std::lock_guard lock(mutex_);
  if (failure_) std::rethrow_exception(failure_);
}

bool CommitQueue::failed() {
  std::lock_guard lock(mutex_);
  return failure_ != nullptr;
}

void CommitQueue::drain() {
  {
    std::unique_lock lock(mutex_);
    idle_.wait(lock, [this] { return (queue_.empty() && !busy_) || failure_; });
  }
  rethrow_failure();
}

double CommitQueue::busy_seconds() {
  std::lock_guard lock(mutex_);
  return busy_seconds_;
}

double CommitQueue::cpu_seconds() {
  std::lock_guard lock(mutex_);
  return cpu_seconds_;
}

namespace {

double thread_cpu() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec) / 1e9;
}

} // namespace

// One transaction for all; when it is refused, batch by batch, so that a batch the store refuses
// (a worker's bad entry) does not take the good ones queued before it along: those are committed,
// the refused one's failure goes up, and nothing after it is done.
void CommitQueue::commit_together(std::vector<store::IndexEntry> first,
                                  std::vector<std::vector<store::IndexEntry>> more) {
  if (more.empty()) return committer_.commit(std::move(first));
  std::vector<store::IndexEntry> all = first;
  for (const auto& batch : more)
    all.insert(all.end(), batch.begin(), batch.end());
  try {
    committer_.commit(std::move(all));
    return;
  } catch (const std::exception&) {
    // The transaction left nothing behind: the batches again, one at a time.
  }
  committer_.commit(std::move(first));
  for (auto& batch : more)
    committer_.commit(std::move(batch));
}

void CommitQueue::loop() {
  std::unique_lock lock(mutex_);
  for (;;) {
    wake_.wait(lock, [this] { return stop_ || !queue_.empty(); });
    if (queue_.empty() || failure_) {
      // Stopped with nothing left, or a failure: what is queued after a failure is not done (the
      // leaves recorded after a failed commit would claim components the index does not have).
      queue_.clear();
      idle_.notify_all();
      if (stop_) return;
      continue;
    }
    Work work = std::move(queue_.front());
    queue_.pop_front();
    // The COMMITs queued one after another go in one transaction (one sync of the index, not one
    // per worker message: at 1 row per COMMIT the writer managed 100-400 rows/s). An action
    // queued between them still runs after those before it and before those after it.
    std::vector<std::vector<store::IndexEntry>> batches;
    if (std::holds_alternative<std::vector<store::IndexEntry>>(work))
      while (!queue_.empty() && std::holds_alternative<std::vector<store::IndexEntry>>(queue_.front())) {
        batches.push_back(std::move(std::get<std::vector<store::IndexEntry>>(queue_.front())));
        queue_.pop_front();
      }
    busy_ = true;
    lock.unlock();
    const auto began = std::chrono::steady_clock::now();
    const double cpu_began = thread_cpu();
    std::exception_ptr failed;
    try {
      if (auto* entries = std::get_if<std::vector<store::IndexEntry>>(&work))
        commit_together(std::move(*entries), std::move(batches));
      else
        std::get<std::function<void()>>(work)();
    } catch (...) {
      failed = std::current_exception();
    }
    const double spent = std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
    const double cpu = thread_cpu() - cpu_began;
    lock.lock();
    busy_seconds_ += spent;
    cpu_seconds_ += cpu;
    busy_ = false;
    if (failed && !failure_) failure_ = failed;
    if (queue_.empty() || failure_) idle_.notify_all();
  }
}

} // namespace geotandem::runtime::detail
