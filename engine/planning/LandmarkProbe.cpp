#include "planning/LandmarkProbe.hpp"

#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>

#include "contact/RigidSurface.hpp"
#include "eval/SkinPoint.hpp"

namespace orthosim {

Eigen::Vector3d LandmarkProbe::at(const Eigen::Matrix3Xd& x) const {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (const auto& [node, weight] : nodes) p += weight * x.col(node);
  return p;
}

std::vector<LandmarkProbe> landmarkProbes(const CaseModel& model, const std::vector<std::string>& names) {
  const SurfaceMesh& skin = model.tissue.skin;
  const PointEmbedding& embedding = model.skinEmbedding;
  if (skin.numVertices() == 0 || embedding.numPoints() != skin.numVertices())
    throw std::invalid_argument("the case has no display skin to place soft-tissue landmarks on");
  const RigidSurface rest(skin);
  std::vector<LandmarkProbe> out;
  for (const std::string& name : names) {
    const auto it = model.spec.landmarks.find(name);
    if (it == model.spec.landmarks.end())
      throw std::invalid_argument("landmark " + name + ": the case does not give it");
    const SkinPoint p = skinPointNear(rest, skin, it->second);
    if (p.restOffset > kMaxLandmarkSkinOffsetMm) {
      std::ostringstream s;
      s << "landmark " << name << ": " << p.restOffset << " mm from the skin, not a soft-tissue landmark (at most "
        << kMaxLandmarkSkinOffsetMm << " mm)";
      throw std::invalid_argument(s.str());
    }
    std::map<int, double> weights;  // the corners' tetrahedra share nodes
    for (int k = 0; k < 3; ++k) {
      const int v = skin.triangles(k, p.triangle);
      for (const auto& [node, w] : embedding.terms(v)) weights[node] += p.weights[k] * w;
    }
    LandmarkProbe probe;
    probe.name = name;
    probe.nodes.assign(weights.begin(), weights.end());
    probe.rest = placeSkinPoint(skin, p);
    out.push_back(std::move(probe));
  }
  return out;
}

std::vector<std::string> skinLandmarkNames(const CaseModel& model) {
  const SurfaceMesh& skin = model.tissue.skin;
  if (skin.numVertices() == 0) return {};
  const RigidSurface rest(skin);
  std::vector<std::string> out;
  for (const auto& [name, position] : model.spec.landmarks)
    if (std::abs(rest.query(position).distance) <= kMaxLandmarkSkinOffsetMm) out.push_back(name);
  return out;
}

}  // namespace orthosim
