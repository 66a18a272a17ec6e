#pragma once
// The run's own task log (issue 55): one line per task the manager saw finish, written by the
// manager to STORE/task-log.tsv, so that a run can be replayed (bench_scale_model) or examined.
//
// The file is text, tab-separated, one task a line after a header line naming the columns:
//   worker kind leaf leaves start end worker_ms bytes rows empty cpu_ms
// worker: the worker's token; kind: EXTRACT, SEND, MERGE or FINISHED (the final pass); leaf: the
// extracted leaf's node id (-1 for other kinds); leaves: the leaves the task concerns (1 for an
// EXTRACT of one leaf, those of the surface sent or merged, those of the whole surface for FINISHED); start,
// end: seconds since the run started when the manager sent the task and when its result arrived;
// worker_ms: the task's time as the worker measured it (SEND: end - start); bytes: the partial
// surface sent or merged (0 otherwise); rows: index rows the worker committed during the task;
// empty (EXTRACT, MERGE; absent from logs before it): 1 when the worker's surface was empty after
// the task (it dropped it: no SEND or MERGE for those leaves), plus 2 when the EXTRACT's leaves left
// nothing open by themselves. An EXTRACT of a batch has the batch's node as its leaf, and as leaves
// those it extracted (not the finished ones it spanned and skipped). cpu_ms (absent
// before it; -1 for SEND): the worker process's CPU time during the task (user + system).
// merges, merge_leaves, merge_bytes, wire_ms, merge_ms, absorb_ms (EXTRACT; absent before them): the
// merges the worker made inside the batch (the smaller side's leaves and record bytes, summed), its
// time serialising the records and merging them, and its time merging the EXTRACT's surface into
// the one it held (0: it held none): what prices a SEND and a MERGE from a log that has none (a
// 1-worker run's).
// Lines starting with '#' describe the run: "# cube LO0 LO1 LO2 HI0 HI1 HI2 leaf_size N [batch B
// cores C]" first (B: the most leaves an EXTRACT could carry; C: the host's processors),
// and at the end "# manager cpu_seconds S wall_seconds W messages_in I messages_out O rows R
// commit_seconds C workers K commit_cpu_seconds U" (U: the index writer's CPU time, within S). A resumed run appends
// its own block to the file.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "geotandem/volume/box.hpp"

namespace geotandem::runtime {

struct TaskRecord {
  std::string worker;
  std::string kind; // EXTRACT, SEND, MERGE, FINISHED
  std::int64_t leaf = -1;
  std::uint64_t leaves = 0;
  double start = 0, end = 0; // seconds since the run started
  double worker_ms = 0;
  std::uint64_t bytes = 0;
  std::uint64_t rows = 0;
  unsigned empty = 0; // see above
  double cpu_ms = -1; // see above; -1: not recorded
  // The merges inside an EXTRACT's batch (see above).
  std::uint64_t merges = 0, merge_leaves = 0, merge_bytes = 0;
  double wire_ms = 0, merge_ms = 0, absorb_ms = 0;
};

struct TaskLogRun {
  volume::Box cube{};
  std::int64_t leaf_size = 0;
  std::size_t batch = 1;     // the most leaves an EXTRACT could carry (1 in logs before batches)
  std::size_t cores = 0;     // the host's processors (0: not recorded)
  bool empties = false;      // the log has the empty column (the run dropped empty surfaces)
  bool batch_merges = false; // the log has the columns of the merges inside batches
  std::vector<TaskRecord> tasks;
  // From the closing line (0 when the run did not end: a killed manager).
  double manager_cpu_seconds = 0, wall_seconds = 0, commit_seconds = 0;
  double commit_cpu_seconds = -1; // -1: not recorded
  std::uint64_t messages_in = 0, messages_out = 0, rows = 0, workers = 0;
};

inline constexpr const char* kTaskLogName = "task-log.tsv";

// Every run of the file, in order. Throws IoError when it cannot be read, DataError naming the
// line when a line is not a task log's.
std::vector<TaskLogRun> read_task_log(const std::filesystem::path& path);

} // namespace geotandem::runtime
