#pragma once
// The scale model (issue 55, part 4): a run's measured task times and surface sizes, from its task
// log (task_log.hpp), replayed through the real Schedule with N simulated workers. It predicts the
// wall time, the efficiency and which shared part saturates first: the manager (one thread that
// handles every message), the index writer (one thread that commits every row) or the merges near
// the root (the tail of the run, when fewer surfaces are left than workers).
//
// What it assumes (say so when quoting it):
// - a leaf takes the time the recorded run took for the leaf at the same relative position of the
//   cube (the recorded leaf's time, scaled by the ratio of cells when the leaf sizes differ);
// - a partial surface's bytes follow a power law in the leaves it covers, fitted on the recorded
//   SENDs (bytes = k leaves^p, p within [1/2, 1], 2/3 when the SENDs cover one size); a MERGE's and a SEND's time are
//   linear in those bytes, fitted on the recorded ones; the final pass takes its recorded time, scaled
//   with the bytes of the whole cube's surface on another cube;
//   a log with fewer than two SENDs or MERGEs (a 1-worker run) fits them on what its EXTRACTs record
//   instead: the surface sizes and the SEND's time on the merges inside its batches (the records'
//   leaves and bytes, the time to serialise them), the MERGE's time on the merges of each EXTRACT's
//   surface into its worker's (a merge into a large surface, as a MERGE is; at their mean when no
//   batch merged anything, as with leaves too slow to batch), and a MERGE's overhead is an EXTRACT's;
// - the manager spends the recorded CPU per message (its CPU but its index writer's, over its messages) on each of
//   the simulated ones: ASK, the task, DONE and COMMIT per task, chunks and credits per MiB of a
//   surface both ways; the index writer its recorded busy time per leaf extracted;
// - workers start when the recorded ones did (the mean delay to their first task, scaled as a task's
//   time is by the share of a core they get), and a WAIT
//   lasts what the manager says (20 ms);
// - processors: with cores = 0 every worker runs on its own core; with the host's cores, the
//   workers, the manager and the recorded run's other load share them (cpu_share below);
// - small leaves go in batches as the manager hands them out (extract_batch), and a surface whose
//   leaves all left nothing open by themselves is dropped, not sent (when the recorded run did so);
// - a task costs, beyond its own time, the recorded mean overhead of its kind (messages there
//   and back, the shard's sync), and a worker asks again after the recorded median gap (the mean
//   would count the WAITs the replay makes itself).
#include <cstdint>
#include <string>
#include <vector>

#include "geotandem/runtime/task_log.hpp"
#include "geotandem/tandem/block_tree.hpp"

namespace geotandem::runtime {

struct ScaleModelCalibration {
  volume::Box cube{};                          // of the recorded run
  std::int64_t leaf_size = 0;                  // of the recorded run
  std::vector<double> extract;                 // seconds per leaf of the recorded tree, by node id (a batch's
                                               // time spread evenly over its leaves)
  std::vector<char> solid;                     // by node id: 1 when the leaf left something open (not empty)
  bool drops = false;                          // the run dropped empty surfaces (its log says which)
  std::size_t batch = 1;                       // the most leaves an EXTRACT could carry in the recorded run
  double extract_mean = 0;                     // over the recorded leaves
  double bytes_k = 0, bytes_p = 1;             // surface bytes = k * leaves^p
  double merge_fixed = 0, merge_per_byte = 0;  // seconds
  double send_fixed = 0, send_per_byte = 0;    // seconds (the worker's serialise and upload)
  double finish_seconds = 0;                   // of the recorded final pass
  std::uint64_t finish_leaves = 0;             // the leaves it covered
  double manager_per_message = 0;              // CPU seconds
  double index_per_row = 0, rows_per_leaf = 0; // the index writer's seconds per leaf; 1
  double startup = 0;                          // seconds before a worker's first task
  // What a task costs beyond the worker's own time, as the manager saw it (mean of its end -
  // start - the worker's time: messages there and back, the shard's sync before the COMMIT), by
  // kind, and the median gap between a worker's result and its next task (its ASK on the way).
  double overhead_extract = 0, overhead_merge = 0, overhead_finish = 0, gap = 0;
  std::size_t batch_merges = 0; // EXTRACTs whose merges inside the batch the log records
  // The processors (issue 55): the host's cores (from the log; 0: not recorded), the share of a core
  // a worker got in its tasks (its CPU time over its wall time, 1 when not recorded), the manager's
  // share of a core (its CPU over the wall time), and the machine's other load in runnable
  // processes, inferred from them (cores / cpu_share - workers - manager_share; 0 when a worker had a
  // core of its own).
  std::size_t cores = 0;
  double cpu_share = 1, manager_share = 0, background = 0;
  std::size_t recorded_workers = 0;
  double recorded_wall = 0, recorded_manager_cpu = 0;
};

// From one run of a task log. Throws InvalidArgument when the run has no EXTRACT.
ScaleModelCalibration calibrate(const TaskLogRun& run);

struct ScalePrediction {
  std::size_t workers = 0;
  double wall = 0;         // seconds
  double work = 0;         // the sum of every simulated task's time
  double efficiency = 0;   // work of one worker's replay / (workers * wall), filled by the caller
  double manager_busy = 0; // share of the wall time the manager's thread is busy
  double index_busy = 0;   // share of the wall time the index writer is busy
  double tail = 0;         // seconds from the last EXTRACT's end to the end of the run
  double manager_wait = 0; // mean seconds a message waited for the manager
  std::uint64_t extract = 0, send = 0, merge = 0, wait = 0;
  std::string saturates; // "manager", "index writer", "merges near the root" or "nothing"
  double cpu_share = 1;  // of a core, per worker (see predict)
};

// A worker's share of a core with `workers` workers on `cores` processors (0: a core each), the
// manager and the recorded background load sharing them fairly.
double cpu_share(const ScaleModelCalibration& c, std::size_t cores, std::size_t workers);

// Replays the model on `tree` (the recorded run's or a larger cube's) with `workers` workers on
// `cores` processors: 0 gives every worker a core of its own and no other load (a cluster); the
// recorded host's cores (c.cores) replay this machine, its background load included. Every task's
// recorded time is scaled by cpu_share(recorded) / cpu_share(replayed) (tasks are taken as CPU-bound,
// and the share as constant over the run: the tail, with fewer busy workers, is predicted slow).
ScalePrediction predict(const ScaleModelCalibration& c, const tandem::BlockTree& tree, std::size_t workers,
                        std::size_t cores = 0);

} // namespace geotandem::runtime
