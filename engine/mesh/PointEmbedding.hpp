#pragma once
// Points carried along by a tetrahedral mesh: each point keeps the barycentric coordinates it has
// at rest in one tet, and follows that tet's nodes. This is how the full-resolution skin is
// recovered from a coarse or fine simulation, so both results are shown on the same skin.
//
// A full-resolution skin vertex may lie slightly outside a coarse mesh (its boundary cuts the
// curved skin by up to a few mm). Such a point takes the tet nearest to it and keeps its
// unclamped barycentric coordinates there: the affine map of that tet extended past its faces. At
// rest every point is then reproduced exactly, and any affine deformation is followed exactly.
#include <Eigen/Core>

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
  // Tet carrying point i and its 4 barycentric weights (summing to 1; negative outside the tet).
  const Eigen::VectorXi& tets() const { return tet_; }
  const Eigen::Matrix4Xi& nodes() const { return nodes_; }
  const Eigen::Matrix4Xd& weights() const { return weights_; }
  // Distance at rest from point i to the mesh (mm); 0 for points inside.
  const Eigen::VectorXd& outsideDistance() const { return outside_; }

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
  int numNodes_ = 0;
  Eigen::VectorXi tet_;
  Eigen::Matrix4Xi nodes_;
  Eigen::Matrix4Xd weights_;
  Eigen::VectorXd outside_;
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
