#pragma once
// The bonded tissue group of a bone that comes without one (the ArtiSynth face gives a
// node set for the mandible but none for the maxilla): the candidate tissue nodes, typically the
// deep (bone-side) surface, that lie within a distance of the bone surface. Distance is unsigned
// distance to the surface, so nodes a little inside the bone (segmentations overlap) count too.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "mesh/SurfaceMesh.hpp"

namespace orthosim {

constexpr double kDefaultBoneContactDistance = 2.0;  // mm

struct BoneContact {
  std::vector<int> nodes;         // selected nodes, in candidate order
  std::vector<double> distances;  // mm, distances[k] belongs to nodes[k]
  int candidates = 0;             // how many candidates were tested
  double maxDistance = 0.0;       // mm, the selection bound (inclusive)
  double nearestCandidate = 0.0;  // mm, over all candidates: how far off an empty result was

  int count() const { return static_cast<int>(nodes.size()); }
  bool empty() const { return nodes.empty(); }
  // Of the selected nodes' distances; 0 when nothing was selected. The median of an even count is
  // the mean of the middle two.
  double minDistance() const;
  double medianDistance() const;
  double maxSelectedDistance() const;
  // One line for logs and warnings, e.g. "maxilla: 312 of 2180 candidate nodes within 2 mm of the
  // bone (distance min 0.001, median 0.48, max 1.99 mm)" or, when empty, "maxilla: no candidate
  // node within 2 mm of the bone (nearest 7.3 mm)".
  std::string summary(const std::string& bone) const;
};

// Candidates within maxDistance (mm, inclusive) of the bone surface, which may be open (cropped).
// An empty result is a result, not an error: the caller decides whether to warn. Throws
// std::invalid_argument when a candidate index is out of range, maxDistance is not a positive
// number, or the bone surface has no usable triangle.
BoneContact nodesNearBone(const Eigen::Matrix3Xd& rest, const std::vector<int>& candidates, const SurfaceMesh& bone,
                          double maxDistance = kDefaultBoneContactDistance);

}  // namespace orthosim
