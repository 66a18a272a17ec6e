// The task log: written by the manager, read by the scale model (task_log.hpp).
#include "task_log.hpp"

#include <fstream>
#include <optional>
#include <sstream>

#include "geotandem/core/error.hpp"

namespace geotandem::runtime {

namespace detail {

TaskLogWriter::TaskLogWriter(const std::filesystem::path& path, const volume::Box& cube, std::int64_t leaf_size,
                             std::size_t batch, std::size_t cores)
    : file_(std::fopen(path.c_str(), "ae")) {
  if (!file_) return;
  // A buffer of 1 MiB: a line costs the manager a formatted print, and the buffer goes to the file
  // once a second at most (add()).
  std::setvbuf(file_, nullptr, _IOFBF, std::size_t{1} << 20);
  // A manager killed mid-run leaves its last line cut: this run's lines start on a line of their own.
  {
    std::ifstream before(path, std::ios::binary | std::ios::ate);
    if (before && before.tellg() > 0) {
      before.seekg(-1, std::ios::end);
      char last = '\n';
      if (before.get(last) && last != '\n') std::fputc('\n', file_);
    }
  }
  std::fprintf(file_, "# cube %lld %lld %lld %lld %lld %lld leaf_size %lld batch %zu cores %zu\n",
               static_cast<long long>(cube.lo[0]), static_cast<long long>(cube.lo[1]),
               static_cast<long long>(cube.lo[2]), static_cast<long long>(cube.hi[0]),
               static_cast<long long>(cube.hi[1]), static_cast<long long>(cube.hi[2]),
               static_cast<long long>(leaf_size), batch, cores);
  std::fprintf(file_, "worker\tkind\tleaf\tleaves\tstart\tend\tworker_ms\tbytes\trows\tempty\tcpu_ms\tmerges\t"
                      "merge_leaves\tmerge_bytes\twire_ms\tmerge_ms\tabsorb_ms\n");
}

TaskLogWriter::~TaskLogWriter() {
  if (file_) std::fclose(file_);
}

void TaskLogWriter::add(const TaskRecord& t) {
  if (!file_) return;
  std::fprintf(
      file_, "%s\t%s\t%lld\t%llu\t%.6f\t%.6f\t%.3f\t%llu\t%llu\t%u\t%.3f\t%llu\t%llu\t%llu\t%.3f\t%.3f\t%.3f\n",
      t.worker.c_str(), t.kind.c_str(), static_cast<long long>(t.leaf), static_cast<unsigned long long>(t.leaves),
      t.start, t.end, t.worker_ms, static_cast<unsigned long long>(t.bytes), static_cast<unsigned long long>(t.rows),
      t.empty, t.cpu_ms, static_cast<unsigned long long>(t.merges), static_cast<unsigned long long>(t.merge_leaves),
      static_cast<unsigned long long>(t.merge_bytes), t.wire_ms, t.merge_ms, t.absorb_ms);
  const auto now = std::chrono::steady_clock::now();
  if (now - flushed_ >= std::chrono::seconds(1)) {
    std::fflush(file_);
    flushed_ = now;
  }
}

void TaskLogWriter::close(const TaskLogRun& r) {
  if (!file_) return;
  std::fprintf(file_,
               "# manager cpu_seconds %.6f wall_seconds %.6f messages_in %llu messages_out %llu rows %llu "
               "commit_seconds %.6f workers %llu commit_cpu_seconds %.6f\n",
               r.manager_cpu_seconds, r.wall_seconds, static_cast<unsigned long long>(r.messages_in),
               static_cast<unsigned long long>(r.messages_out), static_cast<unsigned long long>(r.rows),
               r.commit_seconds, static_cast<unsigned long long>(r.workers), r.commit_cpu_seconds);
  std::fflush(file_);
}

} // namespace detail

std::vector<TaskLogRun> read_task_log(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw IoError("cannot read the task log", {path.string()}, "run an extraction with workers first");
  std::vector<TaskLogRun> runs;
  std::string line;
  std::size_t number = 0;
  const auto bad = [&](const std::string& why) {
    return DataError(path.string() + ":" + std::to_string(number) + ": " + why, {path.string()},
                     "a task log is written by the manager (task_log.hpp); do not edit it");
  };
  // A line that does not read is the cut last line of a killed manager when a run's cube line or the
  // end of the file follows it (the next run starts on a line of its own); anywhere else, an error.
  std::optional<DataError> cut;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty()) continue;
    if (cut) {
      if (line.rfind("# cube ", 0) != 0) throw *cut;
      cut.reset();
    }
    std::istringstream f(line);
    if (line.rfind("# cube ", 0) == 0) {
      TaskLogRun run;
      std::string hash, word, leaf_word;
      f >> hash >> word >> run.cube.lo[0] >> run.cube.lo[1] >> run.cube.lo[2] >> run.cube.hi[0] >> run.cube.hi[1] >>
          run.cube.hi[2] >> leaf_word >> run.leaf_size;
      if (f.fail() || leaf_word != "leaf_size") throw bad("a cube line that does not read");
      std::string key;
      std::size_t value = 0;
      while (f >> key >> value) {
        if (key == "batch") run.batch = value;
        if (key == "cores") run.cores = value;
      }
      runs.push_back(std::move(run));
      continue;
    }
    if (line.rfind("# manager ", 0) == 0) {
      if (runs.empty()) throw bad("a closing line before a cube line");
      TaskLogRun& r = runs.back();
      std::string hash, word, key;
      f >> hash >> word;
      while (f >> key) {
        double value = 0;
        if (!(f >> value)) throw bad("the value of " + key + " does not read");
        if (key == "cpu_seconds") r.manager_cpu_seconds = value;
        if (key == "wall_seconds") r.wall_seconds = value;
        if (key == "commit_seconds") r.commit_seconds = value;
        if (key == "messages_in") r.messages_in = static_cast<std::uint64_t>(value);
        if (key == "messages_out") r.messages_out = static_cast<std::uint64_t>(value);
        if (key == "rows") r.rows = static_cast<std::uint64_t>(value);
        if (key == "workers") r.workers = static_cast<std::uint64_t>(value);
        if (key == "commit_cpu_seconds") r.commit_cpu_seconds = value;
      }
      continue;
    }
    if (line.rfind("worker\t", 0) == 0) {
      if (!runs.empty()) {
        runs.back().empties = line.find("\tempty") != std::string::npos;
        runs.back().batch_merges = line.find("\tmerges") != std::string::npos;
      }
      continue;
    }
    if (line[0] == '#') continue;
    if (runs.empty()) throw bad("a task before a cube line");
    TaskRecord t;
    f >> t.worker >> t.kind >> t.leaf >> t.leaves >> t.start >> t.end >> t.worker_ms >> t.bytes >> t.rows;
    if (f.fail() || (runs.back().empties && !(f >> t.empty >> t.cpu_ms)) ||
        (runs.back().batch_merges &&
         !(f >> t.merges >> t.merge_leaves >> t.merge_bytes >> t.wire_ms >> t.merge_ms >> t.absorb_ms))) {
      cut = bad("a task line that does not read");
      continue;
    }
    runs.back().tasks.push_back(std::move(t));
  }
  return runs;
}

} // namespace geotandem::runtime
