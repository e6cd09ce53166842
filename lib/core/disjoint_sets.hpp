#pragma once
// Disjoint sets of the integers 0..n-1 (union-find): which pieces a mesh or a surface falls into.
#include <numeric>
#include <vector>

namespace corofem {

class DisjointSets {
 public:
  explicit DisjointSets(int n) : parent_(static_cast<std::size_t>(n)) {
    std::iota(parent_.begin(), parent_.end(), 0);
  }

  /// The set's representative: its smallest member (halving paths on the way up).
  int find(int i) {
    while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
    return i;
  }

  void join(int a, int b) {
    a = find(a);
    b = find(b);
    if (a < b) parent_[b] = a;
    if (b < a) parent_[a] = b;
  }

 private:
  std::vector<int> parent_;
};

}  // namespace corofem
