#pragma once
// Connected components of the working surface (the seed's section 3.1). Triangles only ever join
// components (a collapse that passes the link condition never splits one), so a union-find over
// component ids suffices. Each component keeps its key (the smallest lattice-edge id ever born in
// it, mesh::Component), one member vertex to start a traversal from, and the number of its edges
// waiting in W: it is finished when that number is zero (gamma intersect V_w is empty).

#include <cstdint>
#include <utility>
#include <vector>

namespace geotandem::tandem::detail {

struct ComponentRecord {
  std::int32_t parent = -1;
  std::uint64_t key = 0;
  // The samples the component encloses, summed over its vertices (Layer::vertex_samples).
  std::int64_t samples = 0;
  std::int64_t waiting = 0; // edges in W with both endpoints in the component
  std::int32_t member = -1; // a live vertex of the component
  bool alive = false;
  bool queued = false; // in the list of possibly finished components
};

class ComponentTable {
public:
  std::int32_t create(std::uint64_t key, std::int32_t member, std::int64_t samples = 0) {
    const auto id = static_cast<std::int32_t>(records_.size());
    ComponentRecord r;
    r.parent = id;
    r.key = key;
    r.samples = samples;
    r.member = member;
    r.alive = true;
    records_.push_back(r);
    ++alive_;
    return id;
  }

  std::int32_t find(std::int32_t c) {
    while (records_[static_cast<std::size_t>(c)].parent != c) {
      auto& r = records_[static_cast<std::size_t>(c)];
      r.parent = records_[static_cast<std::size_t>(r.parent)].parent; // path halving
      c = r.parent;
    }
    return c;
  }

  // Joins two components; returns the root of the union.
  std::int32_t unite(std::int32_t a, std::int32_t b) {
    a = find(a);
    b = find(b);
    if (a == b) return a;
    if (a > b) std::swap(a, b); // deterministic: the older id survives
    ComponentRecord& ra = at(a);
    ComponentRecord& rb = at(b);
    rb.parent = a;
    rb.alive = false;
    ra.key = ra.key < rb.key ? ra.key : rb.key;
    ra.waiting += rb.waiting;
    ra.samples += rb.samples;
    --alive_;
    return a;
  }

  ComponentRecord& at(std::int32_t root) { return records_[static_cast<std::size_t>(root)]; }
  const ComponentRecord& at(std::int32_t root) const { return records_[static_cast<std::size_t>(root)]; }

  // A waiting edge of component c entered (+1) or left (-1) W.
  void add_waiting(std::int32_t c, int delta) {
    const std::int32_t root = find(c);
    ComponentRecord& r = at(root);
    r.waiting += delta;
    if (r.waiting == 0 && !r.queued) {
      r.queued = true;
      maybe_finished_.push_back(root);
    }
  }

  // Roots that may be finished (their waiting count dropped to zero at some point); the caller
  // checks them again. The list is emptied.
  std::vector<std::int32_t> take_maybe_finished() {
    std::vector<std::int32_t> out;
    out.swap(maybe_finished_);
    for (std::int32_t c : out)
      records_[static_cast<std::size_t>(c)].queued = false;
    return out;
  }
  // Puts a root back for a later check (a component kept because dumping is off).
  void requeue(std::int32_t root) {
    ComponentRecord& r = at(root);
    if (!r.queued) {
      r.queued = true;
      maybe_finished_.push_back(root);
    }
  }

  void remove(std::int32_t root) {
    ComponentRecord& r = at(root);
    if (r.alive) --alive_;
    r.alive = false;
  }

  std::size_t alive_count() const { return alive_; }
  std::size_t record_count() const { return records_.size(); }

  // Rebuilds the table with only the live roots, renumbered in order. Returns, for every old id,
  // the new id of its root (-1 when the root is dead); callers rewrite vertices' ids with it.
  std::vector<std::int32_t> compact();

private:
  std::vector<ComponentRecord> records_;
  std::vector<std::int32_t> maybe_finished_;
  std::size_t alive_ = 0;
};

} // namespace geotandem::tandem::detail
