#pragma once
// Small pieces the manager's loop uses: clocks, the process's CPU time and peak memory, random run
// prefixes for tokens, and a Schedule decision as the message that carries it. Internal to the
// runtime.
#include <chrono>
#include <cstdint>
#include <string>

#include "geotandem/runtime/protocol.hpp"
#include "geotandem/runtime/schedule.hpp"
#include "geotandem/tandem/block_tree.hpp"

namespace geotandem::runtime::detail {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point t);
std::int64_t peak_rss_kb(); // of this process, so far (KiB)
double cpu_seconds();       // user + system CPU of this process
std::string random_hex(std::size_t n);

// The message of a decision, without its lease (the manager sets it): EXTRACT with the leaf's
// cells, SEND with its target, MERGE (its size and checksum come with the surface), WAIT 20 ms,
// FINISHED (1: the final pass).
Message task_message(const Decision& d, const tandem::BlockTree& tree);

// The most leaves one EXTRACT may carry: GEOTANDEM_EXTRACT_BATCH when it is a positive integer,
// else 4096.
std::size_t extract_batch_cap();

} // namespace geotandem::runtime::detail
