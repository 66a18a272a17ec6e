#pragma once
// The manager's writer of the task log (geotandem/runtime/task_log.hpp). Internal to the runtime.
#include <chrono>
#include <cstdio>
#include <filesystem>

#include "geotandem/runtime/task_log.hpp"

namespace geotandem::runtime::detail {

class TaskLogWriter {
public:
  // Appends to `path`, with the header line and the cube's line. A file that cannot be opened
  // leaves the log off (the run does not depend on it): ok() says so.
  TaskLogWriter(const std::filesystem::path& path, const volume::Box& cube, std::int64_t leaf_size, std::size_t batch,
                std::size_t cores);
  ~TaskLogWriter();
  TaskLogWriter(const TaskLogWriter&) = delete;
  TaskLogWriter& operator=(const TaskLogWriter&) = delete;

  bool ok() const { return file_ != nullptr; }
  // One line; the lines so far reach the file at most a second after they were added (a manager
  // killed later keeps them for the scale model), without a system call per line.
  void add(const TaskRecord& task);
  // The closing line (see task_log.hpp), then flushed.
  void close(const TaskLogRun& totals);

private:
  std::FILE* file_ = nullptr;
  std::chrono::steady_clock::time_point flushed_ = std::chrono::steady_clock::now();
};

} // namespace geotandem::runtime::detail
