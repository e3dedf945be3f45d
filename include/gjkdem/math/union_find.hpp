#pragma once
// Disjoint sets of 0..n-1 with path halving: the connected pieces of a
// surface (its shells), of an overlap (its patches), of a solid beyond a
// plane.
#include <cstdint>
#include <vector>

namespace gjkdem {

struct UnionFind {
  std::vector<std::uint32_t> parent;

  /// n singletons (memory kept).
  void reset(std::size_t n) {
    parent.resize(n);
    for (std::uint32_t i = 0; i < n; ++i) parent[i] = i;
  }
  /// A new singleton; returns it.
  std::uint32_t add() {
    parent.push_back(static_cast<std::uint32_t>(parent.size()));
    return parent.back();
  }
  std::uint32_t find(std::uint32_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  /// Joins the sets of i and j; true when they were apart.
  bool join(std::uint32_t i, std::uint32_t j) {
    const std::uint32_t a = find(i), b = find(j);
    parent[a] = b;
    return a != b;
  }
};

}  // namespace gjkdem
