#pragma once
// The manager's decisions (the seed's algorithm 6) as a pure state machine over the block tree: no
// sockets, no clocks, no files. The transport feeds it events (a worker joined, asked, finished a
// task, died) and sends the decisions it returns.
//
// A worker that asks gets, in this order:
//   1. MERGE when a surface sent to it has arrived (has_waiting_surface); WAIT while one is still
//      on its way (it must not give its aggregate away meanwhile);
//   2. SEND to a neighbour worker when its aggregate is restricted-adjacent to that worker's and
//      not larger (has_neighbor_worker; the neighbour's aggregate counts the surfaces on their way
//      to it; the smaller side travels, so a large aggregate stays put and its worker extracts);
//   3. EXTRACT of an unprocessed leaf, one restricted-adjacent to its aggregate if there is one
//      (has_unprocessed_block);
//   4. FINISHED: the final one when it holds every leaf and nothing is on its way (it finishes the
//      whole surface and dumps it); then to everyone. Until the run is complete an idle worker gets
//      WAIT instead of the seed's FINISHED, so that it can redo the blocks of a worker that dies.
// A retiring worker (near its walltime) gets no EXTRACT and receives no surface: the surfaces on
// their way to it go to another worker, it MERGEs those already given to it, SENDs what it holds
// to a live worker that is not retiring (a restricted-adjacent one if there is one, else the one
// claiming most leaves: merging surfaces that do not touch is valid, the region becomes their
// union), and is then told FINISHED. With no such worker it gets the final FINISHED if it holds the
// whole surface, else WAITs while one is expected (expect_joins), else is told FINISHED holding its
// leaves (they are re-done).
// A dead or departed worker's leaves, and those of every surface addressed to it or not yet
// received from it, become unprocessed again: they are re-done from the volume.
//
// Cost (issue 55): a decision costs O(m depth log m) for a worker whose aggregate has m maximal
// nodes, whatever the number of leaves and of workers (per-node counts of unprocessed and claimed
// leaves, by face, find the adjacent ones; an owner per node finds the neighbour workers). Only a
// retiring worker's hand-back and a resumed run's last hand-overs look at every worker.
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <vector>

#include "geotandem/runtime/aggregate.hpp"
#include "geotandem/tandem/block_tree.hpp"

namespace geotandem::runtime {

using WorkerId = std::uint32_t;
using TransferId = std::uint64_t;

enum class TaskKind : std::uint8_t { extract, send, merge, wait, finished };
const char* to_string(TaskKind kind);

struct Decision {
  TaskKind kind = TaskKind::wait;
  tandem::NodeId leaf = tandem::kNoNode; // extract: a leaf, or a node (a batch: its leaves but the finished ones)
  std::uint32_t finished = 0;            // extract: leaves of the batch finished already (the worker skips them)
  WorkerId target = 0;                   // send
  TransferId transfer = 0;               // send, merge
  bool final = false;                    // finished: this worker holds the whole surface
};

struct ScheduleCounts {
  std::uint64_t extract = 0, send = 0, merge = 0, wait = 0, finished = 0;
  std::uint64_t redone_leaves = 0; // leaves made unprocessed again by a worker's death
  std::uint64_t handback = 0;      // SENDs of retiring workers (counted in send too)
  std::uint64_t emptied = 0;       // tasks after which the worker's surface was empty (done(..., true))
};

namespace detail {
class LeafCounts;
}

// How many leaves an EXTRACT carries (Schedule::set_batch), the manager's policy and the scale
// model's: a task worth about `target` seconds of a worker's time at `leaf_seconds` a leaf (the mean
// so far; 0: none measured yet, one leaf), at most a quarter of the unprocessed leaves per worker
// (the end of the extraction stays balanced) and at most `cap`; a power of two (a whole subtree in a
// regular tree). batch_seconds() gives the target: kBatchSeconds, or more when the manager's CPU
// per task so far would make it more than kManagerShare of the wall time with `workers` busy.
inline constexpr double kBatchSeconds = 0.025;
inline constexpr double kManagerShare = 0.04;
double batch_seconds(double manager_cpu_per_task, std::size_t workers);
std::size_t extract_batch(double leaf_seconds, std::size_t unprocessed, std::size_t workers, std::size_t cap,
                          double target = kBatchSeconds);

class Schedule {
public:
  // `tree` must outlive the schedule. Every leaf starts unprocessed.
  explicit Schedule(const tandem::BlockTree& tree);
  ~Schedule();
  Schedule(const Schedule&) = delete;
  Schedule& operator=(const Schedule&) = delete;

  // A leaf whose components are already committed in full by an earlier run (resume): never
  // extracted. Only before the first decision. Throws InvalidArgument for a non-leaf.
  void skip(tandem::NodeId leaf);
  // Small leaves in batches (issue 55): an EXTRACT hands out the largest subtree, of at most
  // `leaves` leaves, around the leaf it would have chosen, none of whose leaves a worker claims:
  // each is unprocessed or finished (skipped by a resume, dropped with an empty surface). The
  // worker extracts the unprocessed ones in tree order and merges them bottom-up as one process
  // does; it skips the finished ones (Decision::finished counts them, finished() tells which), whose
  // surfaces are empty, and the batch's node joins its aggregate whole. So the few leaves a killed
  // run finished do not cut a resumed run's tree into smaller batches and more merges: its batches
  // and merges are those of a clean run. 1 (the default): one leaf per EXTRACT, the seed's
  // algorithm. May change between decisions.
  void set_batch(std::size_t leaves) { batch_ = leaves < 1 ? 1 : leaves; }

  // Events. A worker id is joined once; events for unknown or departed workers throw std::logic_error
  // (the transport filters stale messages before they get here).
  void join(WorkerId worker);
  // The worker asks for its next task; it must have no task in progress.
  Decision next(WorkerId worker);
  // The worker finished its task: EXTRACT (its leaf is now in its surface), MERGE, the final
  // FINISHED. For SEND use arrived(). `emptied` (EXTRACT or MERGE): the worker's surface holds
  // nothing after the task, every component of its leaves is committed, and the worker dropped it:
  // the leaves it held are finished (as skipped ones are), it holds nothing, and no SEND or MERGE
  // is ever made for them. A finished leaf is not re-done when its worker dies later.
  void done(WorkerId worker, bool emptied = false);
  // The surface of the sender's SEND reached the manager; the sender is idle again. Returns false
  // when the transfer's target died meanwhile (the bytes are dropped: its leaves are re-done).
  bool arrived(WorkerId sender, TransferId transfer);
  // The worker is near its walltime: from now on it only hands back what it holds (see above).
  void retire(WorkerId worker);
  // Workers launched that have not joined yet: a retiring worker with nobody to hand its surface
  // to waits for them rather than have its leaves re-done.
  void expect_joins(std::size_t workers) { awaited_ = workers; }
  // The worker died or left; returns the leaves that became unprocessed again.
  std::vector<tandem::NodeId> leave(WorkerId worker);

  bool complete() const { return complete_; }
  bool knows(WorkerId worker) const { return workers_.count(worker) != 0; }
  bool busy(WorkerId worker) const;
  bool retiring(WorkerId worker) const;
  // The worker a transfer goes to and comes from; nullopt when it is no longer pending.
  std::optional<WorkerId> transfer_target(TransferId transfer) const;
  std::optional<WorkerId> transfer_source(TransferId transfer) const;
  std::size_t unprocessed() const;
  std::size_t leaves_held(WorkerId worker) const;
  // The leaves a pending transfer carries (0 when it is no longer pending).
  std::size_t transfer_leaves(TransferId transfer) const;
  // The leaves in the worker's surface (with those of a MERGE in progress), in tree order. O(leaves).
  std::vector<tandem::NodeId> held(WorkerId worker) const;
  // The leaves that entered the worker's surface since the last call (by EXTRACT, or in the
  // surfaces it merged, which carry theirs from their sender): when its surface is empty after a
  // task, these and the ones taken before are finished. O(leaves returned).
  std::vector<tandem::NodeId> take_unrecorded(WorkerId worker);
  std::size_t skipped() const { return skipped_; }
  // True for a leaf finished by an earlier run or with an empty surface: never extracted again.
  bool finished(tandem::NodeId leaf) const { return finished_.at(static_cast<std::size_t>(leaf)) != 0; }
  // The leaves under a node of the tree (1 for a leaf): those of an EXTRACT's batch.
  std::size_t leaves_under(tandem::NodeId node) const { return leaves_under_.at(static_cast<std::size_t>(node)); }
  // Leaves finished with an empty surface during this run (done(..., true)).
  std::size_t dropped() const { return dropped_; }
  const ScheduleCounts& counts() const { return counts_; }
  std::size_t live_workers() const { return workers_.size(); }

private:
  struct Worker {
    explicit Worker(const tandem::BlockTree& tree) : held(tree) {}
    Aggregate held; // leaves in its surface (and the leaf it extracts)
    // The surfaces on their way to it, in the order they were addressed to it (by Transfer::order),
    // and those of them that reached the manager and are not being merged yet.
    std::map<std::uint64_t, TransferId> incoming;
    std::set<std::uint64_t> ready;
    std::optional<Decision> task; // in progress
    bool retiring = false;
    std::size_t claimed = 0;           // leaves held plus those on their way to it
    std::vector<tandem::NodeId> fresh; // see take_unrecorded()
  };
  struct Transfer {
    WorkerId from = 0, to = 0;
    Aggregate leaves;
    bool arrived = false;
    bool merging = false;
    std::vector<tandem::NodeId> fresh;
    std::uint64_t order = 0; // in its target's incoming
  };

  Worker& worker(WorkerId id);
  Aggregate claimed(const Worker& w) const; // held plus what is on its way to it
  std::optional<WorkerId> neighbor(WorkerId id);
  std::optional<WorkerId> any_holder(WorkerId id) const;
  std::optional<WorkerId> successor(const Aggregate& leaves, WorkerId id);
  void redirect_incoming(WorkerId id);
  Decision next_retiring(WorkerId id, Worker& w);
  Decision send_to(WorkerId id, Worker& w, WorkerId target);
  tandem::NodeId unprocessed_leaf(const Worker& w) const;
  void release(const Aggregate& leaves, std::vector<tandem::NodeId>& out);
  // The node an EXTRACT hands out for `leaf` (see set_batch) and taking its leaves.
  tandem::NodeId batch_of(tandem::NodeId leaf) const;
  // Returns the finished leaves among them (held from now on, not extracted).
  std::uint32_t take_leaves(WorkerId id, Worker& w, tandem::NodeId node);
  Decision assign(Worker& w, Decision d);
  // The claimed leaves (held or on their way) of each worker as maximal nodes, in owner_.
  void claim(WorkerId id, const Aggregate& leaves);
  void unclaim(WorkerId id, const Aggregate& leaves);
  void claim_node(WorkerId id, tandem::NodeId node);
  void unclaim_node(WorkerId id, tandem::NodeId node);
  void address(TransferId t, WorkerId to); // into `to`'s incoming
  // The first surface that reached the manager for `w` (not merging): now merging. 0: none.
  TransferId take_ready(Worker& w);
  void move_claim(const Aggregate& leaves, WorkerId from, WorkerId to);
  // The owners of the claimed maximal nodes inside `node` on its face (axis, side), but `id`.
  void owners_on_face(tandem::NodeId node, int axis, int side, WorkerId id, std::vector<WorkerId>& out) const;

  const tandem::BlockTree& tree_;
  std::map<WorkerId, Worker> workers_;
  std::map<TransferId, Transfer> transfers_;
  std::vector<char> unprocessed_; // per node id
  std::size_t unprocessed_count_ = 0;
  std::unique_ptr<detail::LeafCounts> open_;  // unprocessed leaves
  std::unique_ptr<detail::LeafCounts> taken_; // leaves a live worker claims
  std::vector<WorkerId> owner_;               // per node: the worker claiming it as a maximal node, 0: none
  std::vector<std::uint32_t> leaves_under_;   // per node
  TransferId next_transfer_ = 1;
  std::uint64_t next_order_ = 1;
  bool started_ = false;
  bool complete_ = false;
  std::size_t skipped_ = 0;
  std::size_t dropped_ = 0;
  // Per node id: 1 for a leaf finished before this run (skipped) or during it with an empty surface
  // (dropped); such a leaf is never extracted again. A finished leaf may be held again (a batch took
  // it in): `loose_` counts those no live worker claims.
  std::vector<char> finished_;
  std::size_t loose_ = 0;
  std::size_t batch_ = 1;
  std::size_t awaited_ = 0;
  ScheduleCounts counts_;
};

} // namespace geotandem::runtime
