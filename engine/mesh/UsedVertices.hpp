#pragma once
// New indices of the vertices some triangle uses, in their old order (-1 for an unused one), and
// how many there are: what a surface keeps when triangles were dropped or replaced.
#include <array>
#include <vector>

namespace orthosim {

inline std::vector<int> usedVertexIndex(const std::vector<std::array<int, 3>>& triangles, int vertices, int* used) {
  std::vector<int> index(vertices, -1);
  for (const auto& t : triangles)
    for (int v : t) index[v] = 0;
  int n = 0;
  for (int& i : index)
    if (i == 0) i = n++;
  if (used) *used = n;
  return index;
}

}  // namespace orthosim
