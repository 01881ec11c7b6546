#pragma once
// TetGen's plain-text .node / .ele files. The index base (0 or 1) is taken from the first node
// index in the .node file, as TetGen does; elements use the same base.
#include <string>

#include "mesh/TetMesh.hpp"

namespace orthosim {

struct TetgenMesh {
  TetMesh mesh;
  int indexBase = 0;  // first node index in the .node file
};

// Throws std::runtime_error naming the file and line of any defect.
TetgenMesh readTetgen(const std::string& nodePath, const std::string& elePath);

// Writes positions (3 x n) in TetGen .node format with the given index base.
void writeTetgenNodes(const std::string& path, const Eigen::Matrix3Xd& x, int indexBase);
// Writes tetrahedra (4 x m, 0-based) in TetGen .ele format with the given index base.
void writeTetgenElements(const std::string& path, const Eigen::Matrix4Xi& tets, int indexBase);

}  // namespace orthosim
