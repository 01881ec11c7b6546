#include "eval/FaceRegion.hpp"

#include <sstream>
#include <stdexcept>

namespace orthosim {
namespace {

bool has(const Landmarks& lm, const char* a, const char* b) { return lm.count(a) && lm.count(b); }

}  // namespace

std::vector<char> FaceRegion::mask(const Eigen::Matrix3Xd& points) const {
  std::vector<char> inside(points.cols());
  for (Eigen::Index i = 0; i < points.cols(); ++i) inside[i] = contains(points.col(i));
  return inside;
}

FaceRegion faceRegion(const Landmarks& lm, const AnatomicalFrame& f, const FaceRegionOptions& o) {
  FaceRegion r;
  std::ostringstream text;
  if (has(lm, "tragus_left", "tragus_right")) {
    r.ear = CutPlane{0.5 * (lm.at("tragus_left") + lm.at("tragus_right")), f.anterior};
    text << "anterior of the coronal plane through the tragi";
  } else if (has(lm, "condylion_left", "condylion_right")) {
    const Eigen::Vector3d mid = 0.5 * (lm.at("condylion_left") + lm.at("condylion_right"));
    r.ear = CutPlane{mid - o.earBehindCondylionMm * f.anterior, f.anterior};
    text << "anterior of the coronal plane " << o.earBehindCondylionMm << " mm behind the condylions";
  } else {
    throw std::invalid_argument(
        "region of interest: the case gives neither tragus_left and tragus_right nor condylion_left and "
        "condylion_right");
  }
  if (!lm.count("soft_menton")) throw std::invalid_argument("region of interest: the case does not give soft_menton");
  r.chin = CutPlane{lm.at("soft_menton") - o.belowMentonMm * f.superior, f.superior};
  text << ", above the axial plane " << o.belowMentonMm << " mm below soft_menton";
  r.description = text.str();
  return r;
}

}  // namespace orthosim
