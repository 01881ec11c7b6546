#include "eval/LandmarkError.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "contact/RigidSurface.hpp"
#include "eval/SkinPoint.hpp"

namespace orthosim {

const std::vector<std::string>& softTissueLandmarkNames() {
  static const std::vector<std::string> names{"pronasale", "subnasale",     "labrale_superius", "labrale_inferius",
                                              "stomion",   "soft_pogonion", "soft_menton"};
  return names;
}

bool sameTopology(const SurfaceMesh& a, const SurfaceMesh& b) {
  return a.numVertices() == b.numVertices() && a.triangles.cols() == b.triangles.cols() && a.triangles == b.triangles;
}

std::vector<LandmarkError> landmarkErrors(const std::vector<std::string>& names, const Landmarks& landmarks,
                                          const AnatomicalFrame& frame, const LandmarkSurfaces& s) {
  const RigidSurface rest(s.rest);
  const bool predictedTracks = sameTopology(s.predicted, s.rest);
  const bool referenceTracks = sameTopology(s.reference, s.rest);
  std::unique_ptr<RigidSurface> reference;
  if (predictedTracks && !referenceTracks) reference = std::make_unique<RigidSurface>(s.reference);
  std::vector<LandmarkError> out;
  for (const std::string& name : names) {
    LandmarkError e;
    e.name = name;
    const auto it = landmarks.find(name);
    if (it == landmarks.end()) {
      e.note = "the case does not give it";
      out.push_back(e);
      continue;
    }
    const SkinPoint p = skinPointNear(rest, s.rest, it->second);
    e.restOffset = p.restOffset;
    if (!predictedTracks) {
      e.status = LandmarkStatus::Untracked;
      e.note = "the predicted surface is not the case's skin deformed (other triangles)";
      out.push_back(e);
      continue;
    }
    e.status = LandmarkStatus::Measured;
    e.predicted = placeSkinPoint(s.predicted, p);
    e.referenceCorresponds = referenceTracks;
    e.reference = referenceTracks ? placeSkinPoint(s.reference, p) : reference->query(e.predicted).closest;
    e.note = referenceTracks ? "same skin point on both" : "reference: closest point (error across the surface only)";
    e.error = e.predicted - e.reference;
    e.errorInFrame =
        Eigen::Vector3d(e.error.dot(frame.anterior), e.error.dot(frame.superior), e.error.dot(frame.right));
    out.push_back(e);
  }
  return out;
}

}  // namespace orthosim
