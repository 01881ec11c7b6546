#pragma once
// A perspective camera orbiting a target point, described in the case's anatomical frame so the
// same angles mean the same view of any patient: azimuth turns about the superior axis (0: in
// front of the face, +90: at the patient's right), elevation tilts above (+) or below (-) the
// horizontal plane. Orbit, zoom and pan change these numbers; the matrices follow from them.
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "scene/Osteotomy.hpp"  // AnatomicalFrame

namespace orthosim::render {

// Where a point lands in an image: pixel column x and row y (origin at the image's top-left
// corner, pixel centres at +0.5) and window depth in [0, 1] as the depth buffer stores it.
struct ProjectedPoint {
  double x = 0, y = 0, depth = 0;
  bool inFront = false;  // in front of the camera and between the near and far planes
};

struct Camera {
  AnatomicalFrame frame;
  Eigen::Vector3d target = Eigen::Vector3d::Zero();  // mm, what the camera looks at
  double distance = 500;                             // mm from the target
  double azimuthDeg = 0;
  double elevationDeg = 0;     // kept within +-89 degrees: the up vector stays defined
  double fieldOfViewDeg = 30;  // vertical
  double sceneRadius = 150;    // mm about the target that near and far planes keep in view

  Eigen::Vector3d viewDirection() const;  // unit, from the eye towards the target
  Eigen::Vector3d eye() const { return target - distance * viewDirection(); }
  Eigen::Vector3d up() const;     // unit, the image's upward direction
  Eigen::Vector3d right() const;  // unit, the image's rightward direction
  double nearPlane() const;
  double farPlane() const;

  Eigen::Matrix4d view() const;
  Eigen::Matrix4d projection(double aspect) const;  // aspect = width / height
  ProjectedPoint project(const Eigen::Vector3d& p, int width, int height) const;
  // Distance in mm along the view direction of a point at window depth `depth` (inverts the
  // projection's non-linear depth, so depth-buffer values compare in mm).
  double eyeDepth(double depth) const;
  // Unit direction from eye() through pixel (x, y) of a width x height image (the inverse of
  // project's x and y): what a click at that pixel points at.
  Eigen::Vector3d rayThroughPixel(double x, double y, int width, int height) const;
  // mm at the target's distance that one pixel spans in an image `height` pixels high.
  double mmPerPixel(int height) const;

  void orbit(double dAzimuthDeg, double dElevationDeg);
  void zoom(double factor);               // > 1 moves closer (distance / factor)
  void pan(double rightMm, double upMm);  // moves the target in the image plane
};

}  // namespace orthosim::render
