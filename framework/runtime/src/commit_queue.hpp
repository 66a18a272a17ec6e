#pragma once
// The manager's index writes, off its message loop: a COMMIT's entries (and what must follow them,
// such as recording the leaves whose components are all committed) are done in order by one
// thread, so that a worker's next task does not wait for the index transaction and its fsync.
// Internal to the runtime.
#include <chrono>
#include <condition_variable>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <variant>
#include <vector>

#include "component_committer.hpp"

namespace geotandem::runtime::detail {

class CommitQueue {
public:
  explicit CommitQueue(ComponentCommitter& committer);
  // Finishes what is queued (a failure then is dropped: rethrow_failure() and drain() report
  // failures) and stops the thread.
  ~CommitQueue();
  CommitQueue(const CommitQueue&) = delete;
  CommitQueue& operator=(const CommitQueue&) = delete;

  void commit(std::vector<store::IndexEntry> entries);
  // Runs `action` on the queue's thread once every commit queued before it is done.
  void then(std::function<void()> action);
  // Throws the first failure of the queue's thread, if any (then nothing more was done).
  void rethrow_failure();
  bool failed();
  // Waits until everything queued is done, then rethrow_failure().
  void drain();
  // The time the thread spent on work (commits and actions), so far.
  double busy_seconds();
  // The CPU time the thread spent on it (user + system), so far.
  double cpu_seconds();

private:
  using Work = std::variant<std::vector<store::IndexEntry>, std::function<void()>>;
  void loop();
  void commit_together(std::vector<store::IndexEntry> first, std::vector<std::vector<store::IndexEntry>> more);

  ComponentCommitter& committer_;
  std::mutex mutex_;
  std::condition_variable wake_, idle_;
  std::deque<Work> queue_;
  bool busy_ = false, stop_ = false;
  double busy_seconds_ = 0, cpu_seconds_ = 0;
  std::exception_ptr failure_;
  std::thread thread_; // last: starts once the members above exist
};

} // namespace geotandem::runtime::detail
