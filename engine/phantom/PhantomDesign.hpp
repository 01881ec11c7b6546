#pragma once
// The numbers the phantom is built from (mm; +x posterior, +y patient's right, +z superior; the
// condylion tops at z = 0, x = -3), shared by the skull, mandible, skin and oral cavity so that
// they fit together: occlusal plane, dental arches and teeth, and what each variant changes.
#include <Eigen/Core>
#include <vector>

namespace orthosim::phantom {

// How a variant differs from class I: all of it happens to the mandible (the maxilla is the same
// in every variant), and the lower face follows.
struct VariantShape {
  double advance = 0;          // chin and lower arch forward (-x), mm; negative: set back
  double chinShift = 0;        // chin and lower arch towards +y (patient's right), mm
  double openRotation = 0;     // mandible turned down and back about the condyles, degrees
  double anteriorStretch = 0;  // extra anterior lower face height (symphysis taller), mm
};
VariantShape variantShape(int variant);  // throws std::invalid_argument for an unknown index

// Where the variant puts a point of the class I mandible (a smooth, invertible map).
Eigen::Vector3d mandibleMap(const VariantShape& v, const Eigen::Vector3d& p);
// The same for the soft tissue: full below the mouth, fading out above the upper lip, so the
// lower face follows the mandible while the upper face stays.
Eigen::Vector3d lowerFaceMap(const VariantShape& v, const Eigen::Vector3d& p);

// Height of the occlusal plane at x (mm): the gap between the arches is centred on it.
double occlusalZ(double x);
constexpr double kOcclusalSlope = 0.12;  // rises 0.12 mm per mm towards the back
constexpr double kToothGap = 1.5;        // vertical gap between upper and lower crowns in class I

// A tooth along an arch: arc length of its mesial and distal ends from the midline, crown height
// (cervical line to tip) and crown half thickness (bucco-lingual / 2).
struct Tooth {
  const char* name;
  double start, end, height, halfThickness;
};
const std::vector<Tooth>& upperTeeth();  // central incisor ... second molar, one side
const std::vector<Tooth>& lowerTeeth();

// Crown tip lowering between teeth (0 at a tooth's centre, about 1.5 mm at the contacts).
double scallop(const std::vector<Tooth>& teeth, double s);
// Crown property at arc length s, blended smoothly between neighbouring teeth.
double crownHeight(const std::vector<Tooth>& teeth, double s);
double crownHalfThickness(const std::vector<Tooth>& teeth, double s);

// The upper dental arch: an ellipse around (kArchCentreX, 0) through the crown centres.
constexpr double kArchCentreX = -40.0;
constexpr double kUpperArchA = 41.0, kUpperArchB = 27.0;  // x and y semi-axes
constexpr double kLowerArchA = 37.3, kLowerArchB = 24.5;
Eigen::Vector2d archPoint(double a, double b, double phi);  // phi: 0 at the midline, + to the right
// Arc length from the midline to angle phi, and its inverse (tabulated).
double archLength(double a, double b, double phi);
double archAngle(double a, double b, double s);

constexpr double kStomionZ = -47.75;  // the lips meet here (centre of the mouth slit)
constexpr double kMouthHalfWidth = 24.0;

}  // namespace orthosim::phantom
