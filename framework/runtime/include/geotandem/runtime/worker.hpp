#pragma once
// A worker (the seed's algorithm 5): connects to the manager, says HELLO with its launch token,
// receives the run's settings, then asks for tasks and obeys until FINISHED:
//   EXTRACT a leaf with the extended tandem algorithm and append it to its surface;
//   SEND its surface (it travels through the manager to the worker that will merge it);
//   MERGE a surface received into its own, simplify the seam, dump finished components;
//   FINISHED: the final worker finishes the whole surface and dumps it; the others stop.
// Finished components go to the worker's own shard (STORE/shards/<token>.gts), made durable after
// every task; their index entries go to the manager, which alone writes the index.
#include <chrono>
#include <string>

#include "geotandem/core/cancel.hpp"
#include "geotandem/core/log.hpp"
#include "geotandem/runtime/run_settings.hpp"

namespace geotandem::runtime {

struct WorkerOptions {
  std::string endpoint; // the manager's, e.g. tcp://127.0.0.1:5555
  std::string token;    // the launch token the manager issued; also the shard's name
  std::chrono::milliseconds heartbeat{500};
  // The worker stops when it has heard nothing from the manager for this long.
  std::chrono::milliseconds manager_timeout{10000};
};

// Runs until FINISHED. Returns 0 on a normal end. Throws Error when the manager is gone or
// unreachable, InvalidArgument on a bad token, Cancelled when `cancel` is set (SIGTERM, Ctrl-C),
// and what the volume and the store throw.
int run_worker(const WorkerOptions& options, const VolumeFactory& factory, Logger& log, const CancelToken& cancel);

} // namespace geotandem::runtime
