#pragma once
// Disjoint sets over dense ids, with path halving and union by index (the smaller root wins, which
// keeps results independent of the order of unions within a component).

#include <cstdint>
#include <numeric>
#include <vector>

namespace geotandem::mesh::detail {

class UnionFind {
public:
  explicit UnionFind(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), std::uint32_t{0}); }

  std::uint32_t find(std::uint32_t x) {
    while (parent_[x] != x)
      x = parent_[x] = parent_[parent_[x]];
    return x;
  }
  void unite(std::uint32_t a, std::uint32_t b) {
    a = find(a);
    b = find(b);
    if (a < b)
      parent_[b] = a;
    else if (b < a)
      parent_[a] = b;
  }

private:
  std::vector<std::uint32_t> parent_;
};

} // namespace geotandem::mesh::detail
