#pragma once
// The connected pieces of a surface (triangles sharing vertices), each as a surface of its own.
#include <array>
#include <vector>

#include "mesh/DisjointSets.hpp"
#include "mesh/SurfaceMesh.hpp"
#include "mesh/UsedVertices.hpp"

namespace orthosim {

inline std::vector<SurfaceMesh> surfacePieces(const SurfaceMesh& mesh) {
  DisjointSets sets(mesh.numVertices());
  for (int t = 0; t < mesh.numTriangles(); ++t) {
    sets.join(mesh.triangles(0, t), mesh.triangles(1, t));
    sets.join(mesh.triangles(0, t), mesh.triangles(2, t));
  }
  std::vector<int> pieceOf(mesh.numVertices(), -1);
  std::vector<std::vector<std::array<int, 3>>> triangles;
  for (int t = 0; t < mesh.numTriangles(); ++t) {
    int& piece = pieceOf[sets.find(mesh.triangles(0, t))];
    if (piece < 0) piece = int(triangles.size()), triangles.emplace_back();
    triangles[piece].push_back({mesh.triangles(0, t), mesh.triangles(1, t), mesh.triangles(2, t)});
  }
  std::vector<SurfaceMesh> out;
  for (const auto& tris : triangles) {
    int used = 0;
    const std::vector<int> index = usedVertexIndex(tris, mesh.numVertices(), &used);
    SurfaceMesh piece;
    piece.vertices.resize(3, used);
    for (int v = 0; v < mesh.numVertices(); ++v)
      if (index[v] >= 0) piece.vertices.col(index[v]) = mesh.vertices.col(v);
    piece.triangles.resize(3, int(tris.size()));
    for (size_t t = 0; t < tris.size(); ++t)
      for (int c = 0; c < 3; ++c) piece.triangles(c, int(t)) = index[tris[t][c]];
    out.push_back(std::move(piece));
  }
  return out;
}

}  // namespace orthosim
