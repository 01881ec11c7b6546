#include "render/ClinicalView.hpp"

#include <algorithm>
#include <cmath>

#include "math/Angles.hpp"
#include "render/RenderError.hpp"

namespace orthosim::render {
namespace {

struct ViewAngles {
  double azimuthDeg, elevationDeg;
};

ViewAngles anglesOf(ClinicalView v) {
  switch (v) {
    case ClinicalView::Frontal:
      return {0, 0};
    case ClinicalView::Profile:
      return {90, 0};
    case ClinicalView::ProfileLeft:
      return {-90, 0};
    case ClinicalView::ThreeQuarter:
      return {45, 0};
    case ClinicalView::ThreeQuarterLeft:
      return {-45, 0};
    case ClinicalView::WormsEye:
      return {0, -45};
    case ClinicalView::BirdsEye:
      return {0, 45};
  }
  return {0, 0};
}

double tanHalf(double deg) { return std::tan(0.5 * deg * kPi / 180.0); }

}  // namespace

const std::vector<std::string>& clinicalViewNames() {
  static const std::vector<std::string> names = {
      "frontal", "profile", "profile_left", "three_quarter", "three_quarter_left", "worms_eye", "birds_eye"};
  return names;
}

ClinicalView parseClinicalView(const std::string& name) {
  const auto& names = clinicalViewNames();
  const auto it = std::find(names.begin(), names.end(), name);
  if (it != names.end()) return static_cast<ClinicalView>(it - names.begin());
  std::string known;
  for (const auto& n : names) known += (known.empty() ? "" : ", ") + n;
  throw RenderError("unknown view '" + name + "' (views: " + known + ")");
}

const std::string& clinicalViewName(ClinicalView view) { return clinicalViewNames()[static_cast<size_t>(view)]; }

void frameCamera(Camera& camera, const Eigen::Matrix3Xd& points, double aspect, double margin) {
  if (points.cols() == 0) throw RenderError("cannot frame a view on no points");
  if (!(aspect > 0)) throw RenderError("image aspect ratio must be positive");
  // Centre the target on the points' extent across the image, then back off until every point is
  // inside both half-angles: a point (x, y) across and z towards the eye needs D >= z + |x| / tan.
  const Eigen::Vector3d r = camera.right(), u = camera.up(), toEye = -camera.viewDirection();
  const Eigen::Vector3d centre = points.rowwise().mean();
  const Eigen::Matrix3Xd d = points.colwise() - centre;
  const Eigen::RowVectorXd x = r.transpose() * d, y = u.transpose() * d;
  const Eigen::Vector3d target =
      centre + 0.5 * (x.maxCoeff() + x.minCoeff()) * r + 0.5 * (y.maxCoeff() + y.minCoeff()) * u;
  const Eigen::Matrix3Xd e = points.colwise() - target;
  const double tv = tanHalf(camera.fieldOfViewDeg) / (1 + margin), th = tv * aspect;
  double distance = 0;
  for (Eigen::Index i = 0; i < e.cols(); ++i) {
    const double z = toEye.dot(e.col(i));
    distance = std::max({distance, z + std::abs(r.dot(e.col(i))) / th, z + std::abs(u.dot(e.col(i))) / tv});
  }
  camera.target = target;
  camera.distance = distance;
  camera.sceneRadius = 1.01 * e.colwise().norm().maxCoeff();
}

Camera clinicalCamera(ClinicalView view, const AnatomicalFrame& frame, const Eigen::Matrix3Xd& points, double aspect) {
  Camera c;
  c.frame = frame;
  c.azimuthDeg = anglesOf(view).azimuthDeg;
  c.elevationDeg = anglesOf(view).elevationDeg;
  frameCamera(c, points, aspect);
  return c;
}

}  // namespace orthosim::render
