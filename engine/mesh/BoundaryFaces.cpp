#include "mesh/BoundaryFaces.hpp"

#include <algorithm>
#include <array>
#include <vector>

namespace orthosim {

Eigen::Matrix3Xi boundaryFaces(const TetMesh& mesh) {
  // Faces of a positive tet (0,1,2,3), each oriented away from the vertex it leaves out.
  static const int faceOf[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  struct Face {
    std::array<int, 3> key;       // sorted nodes: equal for the two tets sharing the face
    std::array<int, 3> oriented;  // as the tet sees it
  };
  std::vector<Face> faces;
  faces.reserve(4 * static_cast<size_t>(mesh.numTets()));
  for (int e = 0; e < mesh.numTets(); ++e)
    for (const auto& f : faceOf) {
      Face face;
      for (int a = 0; a < 3; ++a) face.oriented[a] = mesh.tets(f[a], e);
      face.key = face.oriented;
      std::sort(face.key.begin(), face.key.end());
      faces.push_back(face);
    }
  std::sort(faces.begin(), faces.end(), [](const Face& a, const Face& b) { return a.key < b.key; });

  std::vector<std::array<int, 3>> boundary;
  for (size_t i = 0; i < faces.size();) {
    size_t j = i;
    while (j < faces.size() && faces[j].key == faces[i].key) ++j;
    if (j - i == 1) {
      // Start at the smallest node so that equal faces print and compare alike.
      std::array<int, 3> f = faces[i].oriented;
      std::rotate(f.begin(), std::min_element(f.begin(), f.end()), f.end());
      boundary.push_back(f);
    }
    i = j;
  }
  std::sort(boundary.begin(), boundary.end());
  Eigen::Matrix3Xi out(3, boundary.size());
  for (size_t k = 0; k < boundary.size(); ++k)
    out.col(k) = Eigen::Vector3i(boundary[k][0], boundary[k][1], boundary[k][2]);
  return out;
}

}  // namespace orthosim
