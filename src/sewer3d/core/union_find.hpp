#pragma once
/// \file
/// Disjoint sets over 0 .. n − 1 (path halving): which items a set of links joins.

#include <vector>

namespace sewer3d {

class UnionFind {
 public:
  explicit UnionFind(int n) : parent_(static_cast<size_t>(n)) {
    for (int i = 0; i < n; ++i) parent_[static_cast<size_t>(i)] = i;
  }
  int Root(int i) {
    while (parent_[static_cast<size_t>(i)] != i) {
      i = parent_[static_cast<size_t>(i)] = parent_[static_cast<size_t>(parent_[i])];
    }
    return i;
  }
  void Join(int a, int b) { parent_[static_cast<size_t>(Root(a))] = Root(b); }

 private:
  std::vector<int> parent_;
};

}  // namespace sewer3d
