#pragma once
// Disjoint sets over 0..n−1 (union–find with path halving): connected components of meshes and
// graphs, vertices joined by seams.
#include <numeric>
#include <vector>

namespace dresskit::mesh {

class UnionFind {
 public:
  explicit UnionFind(int n = 0) { reset(n); }
  /// n singletons.
  void reset(int n) {
    parent_.resize(static_cast<std::size_t>(n));
    std::iota(parent_.begin(), parent_.end(), 0);
  }
  /// The representative of a's set.
  int find(int a) {
    while (parent_[static_cast<std::size_t>(a)] != a)
      a = parent_[static_cast<std::size_t>(a)] = parent_[static_cast<std::size_t>(parent_[static_cast<std::size_t>(a)])];
    return a;
  }
  /// Joins a's set to b's (b's representative stays).
  void unite(int a, int b) { parent_[static_cast<std::size_t>(find(a))] = find(b); }

 private:
  std::vector<int> parent_;
};

}  // namespace dresskit::mesh
