#include "eval/SkinFigures.hpp"

#include "eval/VertexAreas.hpp"

namespace orthosim {

SkinFigureProbe::SkinFigureProbe(const CaseModel& model, double skinTolerance) {
  const SurfaceMesh& skin = model.tissue.skin;
  if (skin.numVertices() == 0) return;
  vertexArea_ = vertexAreas(skin);
  std::vector<Eigen::Vector3d> points;
  for (const auto& [name, p] : model.spec.landmarks) {
    const double d2 = (skin.vertices.colwise() - p).colwise().squaredNorm().minCoeff();
    if (d2 > skinTolerance * skinTolerance) continue;
    names_.push_back(name);
    points.push_back(p);
  }
  rest_.resize(3, static_cast<Eigen::Index>(points.size()));
  for (size_t i = 0; i < points.size(); ++i) rest_.col(static_cast<Eigen::Index>(i)) = points[i];
  if (!points.empty()) embedding_ = embedPoints(model.scene.mesh, rest_);
}

SkinFigures SkinFigureProbe::figures(const CaseModel& model, const Eigen::Matrix3Xd& x) const {
  SkinFigures f;
  if (model.tissue.skin.numVertices() == 0) return f;
  const Eigen::Matrix3Xd& rest = model.tissue.skin.vertices;
  const Eigen::VectorXd d = (model.skinEmbedding.apply(x) - rest).colwise().norm().transpose();
  Eigen::Index at = 0;
  f.maxDisplacementMm = d.maxCoeff(&at);
  f.maxAt = rest.col(at);
  f.meanDisplacementMm = d.dot(vertexArea_) / vertexArea_.sum();
  if (!names_.empty()) {
    const Eigen::Matrix3Xd moved = embedding_.apply(x);
    for (size_t i = 0; i < names_.size(); ++i) {
      const auto c = static_cast<Eigen::Index>(i);
      f.landmarks.push_back({names_[i], rest_.col(c), moved.col(c) - rest_.col(c)});
    }
  }
  return f;
}

}  // namespace orthosim
