#pragma once
// A CT or cone-beam CT volume as read from a DICOM series: grey values per voxel (Hounsfield units
// for CT once the series' rescale slope and intercept are applied; uncalibrated for most CBCT) and
// their placement in the patient frame of DICOM, LPS millimetres (+x the patient's left, +y
// posterior, +z superior), the frame of io/LabelMapSurfaces.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace orthosim {

struct CtVolume {
  Eigen::Vector3i size = Eigen::Vector3i::Zero();            // voxels along i, j, k
  Eigen::Matrix3d directions = Eigen::Matrix3d::Identity();  // columns: the step of i, j, k in LPS mm
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();          // LPS mm of voxel (0, 0, 0)'s centre
  std::vector<float> values;                                 // i fastest, then j, then k
  std::string modality = "CT";                               // DICOM Modality: CT, or a CBCT's (often CT too)

  Eigen::Vector3d spacing() const { return directions.colwise().norm().transpose(); }
  Eigen::Vector3d position(const Eigen::Vector3d& index) const { return origin + directions * index; }
  long count() const { return long(size[0]) * size[1] * size[2]; }
  long index(int i, int j, int k) const { return i + long(size[0]) * (j + long(size[1]) * k); }
};

}  // namespace orthosim
