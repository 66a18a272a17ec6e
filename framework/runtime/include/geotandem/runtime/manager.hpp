#pragma once
// The manager (the seed's algorithm 6 over ZeroMQ): binds a ROUTER socket, launches local workers
// if asked, answers every worker's request with the Schedule's decision, relays the partial
// surfaces of SEND to the worker that merges them, commits the component entries the workers
// report to the store's index (it alone writes the index), and watches heartbeats: a worker silent
// for longer than the lease is dead, its blocks and the surfaces it held are re-done, and a
// replacement is launched; so is one whose task outlasts the task bound (task_timeout). Results
// of an old attempt (a late or replayed message) are ignored.
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "geotandem/core/cancel.hpp"
#include "geotandem/core/log.hpp"
#include "geotandem/core/progress.hpp"
#include "geotandem/runtime/launcher.hpp"
#include "geotandem/runtime/protocol.hpp"
#include "geotandem/runtime/run_settings.hpp"
#include "geotandem/store/store.hpp"
#include "geotandem/tandem/simplify.hpp"

namespace geotandem::runtime {

struct ManagerOptions {
  // Where the manager listens; "tcp://127.0.0.1:*" picks a free loopback port.
  std::string bind = "tcp://127.0.0.1:*";
  RunSettings settings;
  // Local workers to launch at the start (0: none; workers started elsewhere connect with a token
  // from Manager::new_token()).
  std::size_t workers = 1;
  // The worker's command line without its --connect and --token, e.g. {"/usr/bin/geotandem", "worker"}.
  std::vector<std::string> worker_command;
  std::chrono::milliseconds heartbeat{500};
  std::chrono::milliseconds lease{2500}; // silent this long: dead
  // A task not finished after the larger of this and 10 times the longest task the run has
  // finished so far is taken back: its worker is treated as dead (its blocks are re-done from the
  // volume, a replacement starts, whatever it sends later is ignored). So is a worker that has
  // not asked for a task this long after joining. A worker that heartbeats but never finishes
  // cannot hold a run forever. GEOTANDEM_TASK_TIMEOUT_SECONDS in `geotandem extract` and
  // `run-workflow`.
  std::chrono::milliseconds task_timeout{std::chrono::minutes(30)};
  std::chrono::milliseconds connect_timeout{60000};
  std::size_t max_restarts = 16; // replacement workers launched after deaths, at most
  std::size_t max_message = kDefaultMaxMessage;
  std::uint64_t max_surface = kDefaultMaxSurface; // a partial surface above this is refused
  // The partial surfaces waiting for their MERGE are held in memory up to this many bytes; past it
  // they wait on disk, in the directory beside the store named like it with ".relay" appended.
  std::uint64_t relay_memory = std::uint64_t{1} << 30;
};

struct ManagerReport {
  std::size_t workers = 0; // that joined
  std::size_t deaths = 0;
  std::size_t restarts = 0;
  std::uint64_t extract = 0, send = 0, merge = 0, finish = 0; // tasks completed (extract: leaves)
  std::uint64_t extract_tasks = 0;                            // EXTRACTs (a batch is one)
  std::uint64_t redone_leaves = 0;
  std::size_t retirements = 0;   // workers that retired near their walltime
  std::uint64_t handed_back = 0; // leaves in the surfaces they handed to other workers
  double seconds_extract = 0, seconds_merge = 0, seconds_finish = 0; // summed over workers
  std::uint64_t surface_bytes = 0;                                   // partial surfaces relayed
  std::uint64_t largest_surface = 0;
  std::uint64_t relay_peak_held = 0;                        // bytes of waiting surfaces in memory, at most
  std::uint64_t relay_spilled = 0, relay_spilled_bytes = 0; // surfaces that waited on disk
  std::uint64_t bytes_in = 0, bytes_out = 0;                // every frame
  std::uint64_t dropped_messages = 0;                       // damaged, unknown sender, stale lease
  std::uint64_t components = 0, duplicates = 0;
  std::uint64_t repaired = 0;               // damaged records of an earlier run written again
  std::vector<std::uint64_t> repaired_keys; // the first of their keys (at most 20)
  std::size_t leaves = 0;
  std::size_t skipped_leaves = 0;                  // finished by an earlier run (resume): not redone
  double seconds = 0, manager_cpu_seconds = 0;     // the run's wall time; CPU the manager used in it
  std::uint64_t messages_in = 0, messages_out = 0; // frames the manager received and sent
  double commit_seconds = 0;                       // the index writer's busy time (its own thread)
  std::int64_t manager_peak_rss_kb = 0;            // of the manager's process, so far
  std::int64_t worker_peak_rss_kb = 0;             // the largest over the workers
  // Of the whole surface, as the final worker reports it (totals travel with the partial surfaces):
  // every counter of the collapse loop over every leaf extracted in this run, among them its
  // marching-cubes triangles (counters.input_triangles) and collapses (counters.collapses).
  tandem::SimplifyCounters counters;
  // The most triangles the workers' surfaces held together, as they reported after each task
  // (surfaces on their way between workers are not counted).
  std::uint64_t peak_held_triangles = 0;

  std::string to_json() const;
};

// The collapse loop's counters as a JSON object keyed by SimplifyCounters::names: the text of a
// worker's DONE after FINISHED, and the run statistics' "counters". Back from it: unknown keys are
// ignored and missing ones stay 0; throws ProtocolError when the text is not such an object.
std::string counters_to_json(const tandem::SimplifyCounters& counters);
tandem::SimplifyCounters counters_from_json(const std::string& text);

class Manager {
public:
  // Binds the socket. `store` must be writable; `launcher` may be null (workers connect on their
  // own). Everything passed must outlive the manager. Throws IoError when the endpoint cannot be
  // bound, InvalidArgument on invalid settings.
  Manager(ManagerOptions options, store::ComponentStore& store, Launcher* launcher, Logger& log, Progress& progress,
          const CancelToken& cancel);
  ~Manager();
  Manager(const Manager&) = delete;
  Manager& operator=(const Manager&) = delete;

  // The bound endpoint (with the port chosen).
  const std::string& endpoint() const;
  // A token a worker started elsewhere may connect with.
  std::string new_token();

  // Runs the extraction to the end. Throws Error when no worker connects within the timeout, when
  // a worker reports a failed task (naming the worker and the block), Cancelled on cancel (the
  // workers are stopped; what was committed stays).
  ManagerReport run();

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

} // namespace geotandem::runtime
