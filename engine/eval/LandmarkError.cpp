#include "eval/LandmarkError.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "contact/RigidSurface.hpp"

namespace orthosim {
namespace {

struct SkinPoint {
  int triangle = -1;
  Eigen::Vector3d weights = Eigen::Vector3d::Zero();  // barycentric, of the triangle's corners
};

SkinPoint locate(const SurfaceMesh& skin, const Eigen::Vector3d& closest, int t) {
  const Eigen::Vector3d a = skin.vertices.col(skin.triangles(0, t)), b = skin.vertices.col(skin.triangles(1, t)),
                        c = skin.vertices.col(skin.triangles(2, t));
  const Eigen::Vector3d n = (b - a).cross(c - a);
  const double w0 = (b - closest).cross(c - closest).dot(n) / n.squaredNorm();
  const double w1 = (c - closest).cross(a - closest).dot(n) / n.squaredNorm();
  return {t, Eigen::Vector3d(w0, w1, 1 - w0 - w1)};
}

Eigen::Vector3d place(const SurfaceMesh& s, const SkinPoint& p) {
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) x += p.weights[k] * s.vertices.col(s.triangles(k, p.triangle));
  return x;
}

}  // namespace

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
    const SurfacePoint onRest = rest.query(it->second);
    e.restOffset = std::abs(onRest.distance);
    if (!predictedTracks) {
      e.status = LandmarkStatus::Untracked;
      e.note = "the predicted surface is not the case's skin deformed (other triangles)";
      out.push_back(e);
      continue;
    }
    const SkinPoint p = locate(s.rest, onRest.closest, onRest.triangle);
    e.status = LandmarkStatus::Measured;
    e.predicted = place(s.predicted, p);
    e.referenceCorresponds = referenceTracks;
    e.reference = referenceTracks ? place(s.reference, p) : reference->query(e.predicted).closest;
    e.note = referenceTracks ? "same skin point on both" : "reference: closest point (error across the surface only)";
    e.error = e.predicted - e.reference;
    e.errorInFrame =
        Eigen::Vector3d(e.error.dot(frame.anterior), e.error.dot(frame.superior), e.error.dot(frame.right));
    out.push_back(e);
  }
  return out;
}

}  // namespace orthosim
