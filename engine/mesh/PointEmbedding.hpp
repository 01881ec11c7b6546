#pragma once
// Points carried along by a tetrahedral mesh: each point keeps the barycentric coordinates it has
// at rest in one tet, and follows that tet's nodes. This is how the full-resolution skin is
// recovered from a coarse or fine simulation, so both results are shown on the same skin.
//
// A full-resolution skin vertex may lie outside a coarse mesh (its boundary cuts the curved skin
// by up to a few mm). Such a point p is carried by its nearest point q on the mesh (which lies in
// a boundary tet) and its offset p - q, turned and stretched by the deformation gradient at q:
// x(p) = x(q) + F(q) (p - q), where F(q) interpolates, over q's tet, the gradients averaged at its
// nodes (by volume over the tets at each node). At rest every point is reproduced exactly and any
// affine deformation is followed exactly; and since F(q) varies continuously, neighbouring points
// whose nearest tets differ stay neighbours (the unclamped extension of each point's own nearest
// tet, used before, let such points part by the tets' different gradients times the offset).
#include <Eigen/Core>
#include <utility>
#include <vector>

#include "mesh/TetMesh.hpp"

namespace orthosim {

struct EmbeddingOptions {
  // Points farther than this from every tet (mm) are refused: they are not on this mesh's skin.
  double maxOutsideDistance = 10.0;
  // A point is inside a tet when none of its barycentric coordinates is below -insideTolerance
  // (dimensionless); points on shared faces and the nodes themselves then count as inside.
  double insideTolerance = 1e-9;
};

class PointEmbedding {
 public:
  PointEmbedding() = default;

  int numPoints() const { return static_cast<int>(tet_.size()); }
  // Tet holding point i (for a point outside: its nearest point on the mesh) and the 4 barycentric
  // weights of that point in it (>= 0, summing to 1).
  const Eigen::VectorXi& tets() const { return tet_; }
  const Eigen::Matrix4Xi& nodes() const { return nodes_; }
  const Eigen::Matrix4Xd& weights() const { return weights_; }
  // Distance at rest from point i to the mesh (mm); 0 for points inside.
  const Eigen::VectorXd& outsideDistance() const { return outside_; }
  // Offset at rest of point i from its nearest point on the mesh (zero inside).
  const Eigen::Matrix3Xd& offsets() const { return offset_; }
  // Point i as a linear combination of node positions (node, weight), by node: the 4 tet nodes
  // for a point inside, those and their neighbours' for one outside. For linear uses (Jacobians).
  std::vector<std::pair<int, double>> terms(int i) const;

  // For callers to warn about: how many points lie outside the mesh, how far at most, and how far
  // on average over those points (0 when none is outside).
  int numOutside() const;
  double maxOutsideDistance() const;
  double meanOutsideDistance() const;

  // The points with the mesh's nodes at `deformedNodes` (3 x numNodes of the embedding mesh).
  // Throws std::invalid_argument when the node count differs from the embedding mesh's.
  Eigen::Matrix3Xd apply(const Eigen::Matrix3Xd& deformedNodes) const;

 private:
  friend PointEmbedding embedPoints(const TetMesh&, const Eigen::Matrix3Xd&, const EmbeddingOptions&);
  // Volume-averaged deformation gradients at the given nodes (slots of gradNodes_).
  std::vector<Eigen::Matrix3d> nodeGradients(const Eigen::Matrix3Xd& deformedNodes) const;

  int numNodes_ = 0;
  Eigen::VectorXi tet_;
  Eigen::Matrix4Xi nodes_;
  Eigen::Matrix4Xd weights_;
  Eigen::VectorXd outside_;
  Eigen::Matrix3Xd offset_;
  // Points outside, the slots of their tets' nodes in gradNodes_ (4 per point, in nodes_ order),
  // and for each slot the tets at that node (CSR into the compact tet arrays below).
  std::vector<int> away_;
  Eigen::Matrix4Xi slots_;
  std::vector<int> gradNodes_, gradStart_, gradTet_;
  Eigen::Matrix4Xi tetNodes_;
  std::vector<Eigen::Matrix3d> tetInverse_;  // [X1-X0, X2-X0, X3-X0]^-1 at rest
  Eigen::VectorXd tetVolume_;
};

// Embeds `points` (3 x n, mm) in the rest configuration of `mesh`, which must be valid
// (validateMesh). Throws std::invalid_argument naming the point for a non-finite point, and
// naming the point and its distance for a point farther than options.maxOutsideDistance from the
// mesh (the first such point by index). Finds the tet holding a point in a uniform grid of tet
// bounding boxes, and the tet nearest to a point outside through the engine's point-to-surface
// query on the mesh boundary (mesh/SurfaceDistance); in parallel over the points, and the result
// does not depend on the thread count.
PointEmbedding embedPoints(const TetMesh& mesh, const Eigen::Matrix3Xd& points, const EmbeddingOptions& options = {});

}  // namespace orthosim
