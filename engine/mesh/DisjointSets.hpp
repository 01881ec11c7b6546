#pragma once
// Union-find over 0..n-1 with path halving: the connected pieces of a surface, the loops of its
// border, the corners that meet at a vertex.
#include <numeric>
#include <vector>

namespace orthosim {

struct DisjointSets {
  std::vector<int> parent;
  explicit DisjointSets(int n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  void join(int a, int b) { parent[find(a)] = find(b); }
};

}  // namespace orthosim
