#pragma once
// A triangle surface held on the GPU. Topology, uv and the rest surface are uploaded once; a new
// pose of the same surface uploads only positions and normals (the topology never changes after a
// solve), and a colour-map value per vertex can be uploaded on its own.
#include <Eigen/Core>
#include <vector>

#include "mesh/SurfaceMesh.hpp"
#include "render/GlHandle.hpp"

namespace orthosim::render {

class GpuMesh {
 public:
  // Throws RenderError naming `what` for an empty surface, an index out of range, a vertex that is
  // not finite, or uv that do not match the vertices.
  GpuMesh(const SurfaceMesh& rest, const std::string& what);

  int numVertices() const { return static_cast<int>(weld_.size()); }
  // New positions of the same vertices (3 x numVertices); normals are recomputed.
  void updatePositions(const Eigen::Matrix3Xd& x);
  // One value per vertex (mm) for ColorSource "scalar" and, optionally, a flag per vertex:
  // 0 draws it without a value (grey, e.g. outside a region of interest); empty: all 1.
  void updateScalars(const Eigen::VectorXd& values, const std::vector<char>& inMap = {});
  const Eigen::Matrix3Xd& positions() const { return positions_; }
  void draw() const;

 private:
  void fillNormals(const Eigen::Matrix3Xd& x);

  std::string what_;
  Eigen::Matrix3Xi triangles_;
  std::vector<int> weld_;           // per vertex: the first vertex at the same position (uv seams)
  Eigen::Matrix3Xd positions_;      // current positions, kept for callers (bounds, differences)
  std::vector<float> interleaved_;  // position and normal per vertex, the upload's staging
  GlVertexArray vao_;
  GlBuffer current_, rest_, uv_, scalars_, indices_;
};

}  // namespace orthosim::render
