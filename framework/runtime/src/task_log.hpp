#pragma once
// The manager's writer of the task log (geotandem/runtime/task_log.hpp). Internal to the runtime.
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
  void add(const TaskRecord& task);
  // The closing line (see task_log.hpp), then flushed.
  void close(const TaskLogRun& totals);

private:
  std::FILE* file_ = nullptr;
};

} // namespace geotandem::runtime::detail
