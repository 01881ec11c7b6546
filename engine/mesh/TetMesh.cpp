#include "mesh/TetMesh.hpp"

#include <Eigen/Dense>
#include <cstdio>
#include <stdexcept>

namespace orthosim {

double TetMesh::signedVolume(int e, const Eigen::Matrix3Xd& x) const {
  const auto t = tets.col(e);
  Eigen::Matrix3d d;
  d << x.col(t[1]) - x.col(t[0]), x.col(t[2]) - x.col(t[0]), x.col(t[3]) - x.col(t[0]);
  return d.determinant() / 6.0;
}

double TetMesh::meanEdgeLength() const {
  static const int edges[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  double sum = 0.0;
  for (int e = 0; e < numTets(); ++e)
    for (const auto& ed : edges) sum += (rest.col(tets(ed[0], e)) - rest.col(tets(ed[1], e))).norm();
  return numTets() > 0 ? sum / (6.0 * numTets()) : 0.0;
}

std::vector<int> TetMesh::unusedNodes() const {
  std::vector<char> used(numNodes(), 0);
  for (int e = 0; e < numTets(); ++e)
    for (int a = 0; a < 4; ++a) used[tets(a, e)] = 1;
  std::vector<int> out;
  for (int i = 0; i < numNodes(); ++i)
    if (!used[i]) out.push_back(i);
  return out;
}

namespace {

void validate(const TetMesh& mesh, const std::string& where, int indexBase, bool allowFlat) {
  if (mesh.numNodes() == 0) throw std::runtime_error(where + ": mesh has no nodes");
  if (mesh.numTets() == 0) throw std::runtime_error(where + ": mesh has no tetrahedra");
  for (int i = 0; i < mesh.numNodes(); ++i)
    if (!mesh.rest.col(i).allFinite())
      throw std::runtime_error(where + ": node " + std::to_string(i + indexBase) + " has a non-finite coordinate");
  const double scale = mesh.meanEdgeLength();
  for (int e = 0; e < mesh.numTets(); ++e) {
    for (int a = 0; a < 4; ++a) {
      const int n = mesh.tets(a, e);
      if (n < 0 || n >= mesh.numNodes())
        throw std::runtime_error(where + ": element " + std::to_string(e + indexBase) + " refers to node " +
                                 std::to_string(n + indexBase) + ", outside " + std::to_string(indexBase) + ".." +
                                 std::to_string(mesh.numNodes() - 1 + indexBase));
    }
    const double v = mesh.signedVolume(e, mesh.rest);
    const double tiny = 1e-12 * scale * scale * scale;
    if (!(v > tiny) && !(allowFlat && v > -tiny)) {
      // Where, so that a meshing failure can be traced to the surfaces there (a thin gap, a fold).
      Eigen::Vector3d c = Eigen::Vector3d::Zero();
      for (int a = 0; a < 4; ++a) c += 0.25 * mesh.rest.col(mesh.tets(a, e));
      char at[96];
      std::snprintf(at, sizeof at, " at (%.1f, %.1f, %.1f)", c.x(), c.y(), c.z());
      throw std::runtime_error(where + ": element " + std::to_string(e + indexBase) + at +
                               (v < 0 ? " is inverted (negative volume " : " is degenerate (volume ") +
                               std::to_string(v) + " mm^3)");
    }
  }
}

}  // namespace

void validateMesh(const TetMesh& mesh, const std::string& where, int indexBase) {
  validate(mesh, where, indexBase, false);
}

void validateMeshAllowingFlat(const TetMesh& mesh, const std::string& where) { validate(mesh, where, 0, true); }

}  // namespace orthosim
