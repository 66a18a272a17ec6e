#pragma once
// The manager's schedule and aggregates as they were on main before issue 55 (O(size of the tree)
// per decision), kept as the oracle of schedule_equivalence_test.cpp: the new Schedule must make
// the same decisions under the same events. Not used by the runtime.
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include "geotandem/runtime/schedule.hpp"
#include "geotandem/tandem/block_tree.hpp"

namespace geotandem::runtime::reference {

using runtime::Decision;
using runtime::ScheduleCounts;
using runtime::TaskKind;
using runtime::TransferId;
using runtime::WorkerId;

class Aggregate {
public:
  // An empty aggregate over `tree`'s leaves. `tree` must outlive it.
  explicit Aggregate(const tandem::BlockTree& tree);

  bool empty() const { return count_ == 0; }
  std::size_t size() const { return count_; } // leaves held
  bool holds(tandem::NodeId leaf) const;
  // Throws InvalidArgument when `leaf` is not a leaf of the tree.
  void add(tandem::NodeId leaf);
  void add(const Aggregate& other);
  void clear();
  // The leaves held, in tree order.
  std::vector<tandem::NodeId> leaves() const;

  // The maximal complete nodes (see above), in tree order.
  std::vector<tandem::NodeId> maximal_nodes() const;
  // The seed's restricted adjacency between two aggregates: some maximal node a of this one and b
  // of `other` with b in the subtree of brother(a) and restricted_adjacent(a, b), or the same with
  // the roles swapped. False when either is empty.
  bool adjacent(const Aggregate& other) const;
  // The same test against a single node (a leaf that is not processed yet).
  bool adjacent(tandem::NodeId node) const;

private:
  const tandem::BlockTree* tree_;
  std::vector<char> leaf_; // per node id: 1 when the node is a leaf held here
  // Per node id: 1 for a leaf, shared by every aggregate of the tree.
  std::shared_ptr<const std::vector<char>> is_leaf_;
  std::size_t count_ = 0;
};

// True when the tree nodes a and b (disjoint subtrees) pass the seed's restricted adjacency in one
// direction or the other.

class Schedule {
public:
  // `tree` must outlive the schedule. Every leaf starts unprocessed.
  explicit Schedule(const tandem::BlockTree& tree);

  // A leaf whose components are already committed in full by an earlier run (resume): never
  // extracted. Only before the first decision. Throws InvalidArgument for a non-leaf.
  void skip(tandem::NodeId leaf);

  // Events. A worker id is joined once; events for unknown or departed workers throw std::logic_error
  // (the transport filters stale messages before they get here).
  void join(WorkerId worker);
  // The worker asks for its next task; it must have no task in progress.
  Decision next(WorkerId worker);
  // The worker finished its task: EXTRACT (its leaf is now in its surface), MERGE, the final
  // FINISHED. For SEND use arrived().
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
  // The leaves in the worker's surface (with those of a MERGE in progress), in tree order.
  std::vector<tandem::NodeId> held(WorkerId worker) const;
  std::size_t skipped() const { return skipped_; }
  const ScheduleCounts& counts() const { return counts_; }
  std::size_t live_workers() const { return workers_.size(); }

private:
  struct Worker {
    explicit Worker(const tandem::BlockTree& tree) : held(tree) {}
    Aggregate held; // leaves in its surface (and the leaf it extracts)
    std::vector<TransferId> incoming;
    std::optional<Decision> task; // in progress
    bool retiring = false;
  };
  struct Transfer {
    WorkerId from = 0, to = 0;
    Aggregate leaves;
    bool arrived = false;
    bool merging = false;
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
  Decision assign(Worker& w, Decision d);

  const tandem::BlockTree& tree_;
  std::map<WorkerId, Worker> workers_;
  std::map<TransferId, Transfer> transfers_;
  std::vector<char> unprocessed_; // per node id
  TransferId next_transfer_ = 1;
  bool started_ = false;
  bool complete_ = false;
  std::size_t skipped_ = 0;
  std::size_t dropped_ = 0; // leaves finished with an empty surface (done(..., true))
  std::size_t awaited_ = 0;
  ScheduleCounts counts_;
};

} // namespace geotandem::runtime::reference
