#pragma once
// Three slices of a CT with its segmentation drawn over the grey values, for a surgeon to check the
// thresholds and the split of the jaws before a scan becomes a case: an axial slice through the
// occlusal level (where the front teeth meet), a sagittal one at the bone's midline and a coronal one
// through the condyles. Each pixel maps to LPS mm (origin + column * u + row * v), so that a click on
// an image can become a seed of the split.
#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "volume/CtSegmentation.hpp"
#include "volume/CtVolume.hpp"

namespace orthosim {

struct SegmentationSlice {
  std::string plane;   // "axial", "sagittal" or "coronal"
  std::string placed;  // where the slice lies and why, for the user
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;  // row-major, top row first
  // LPS mm of pixel (0, 0)'s centre, and the step of one column and of one row. Axial: columns run
  // to the patient's left (+x), rows to posterior (+y); sagittal: columns to posterior, rows down;
  // coronal: columns to the left, rows down (the radiological views).
  Eigen::Vector3d origin = Eigen::Vector3d::Zero(), column = Eigen::Vector3d::Zero(), row = Eigen::Vector3d::Zero();
  std::array<long, 5> pixels{};  // pixels of each label (0 outside, CtSegmentation::kTissue ... kAir)
};

struct SegmentationSliceOptions {
  double pixelMm = 0.5;  // at least the scan's own in-plane spacing is used
  int maxPixels = 640;   // along either side; the pixel grows for larger scans
};

// The colours drawn over the grey values: the skin's outline, the skull, the mandible, the air.
struct SliceColours {
  static constexpr std::array<unsigned char, 3> skin{255, 64, 160}, skull{70, 130, 255}, mandible{255, 170, 30},
      air{0, 220, 220};
};

// The axial, sagittal and coronal slices (in that order). Throws std::invalid_argument when the
// segmentation has no bone to place them by.
std::vector<SegmentationSlice> segmentationSlices(const CtVolume& volume, const CtSegmentation& segmentation,
                                                  const SegmentationSliceOptions& options = {});

}  // namespace orthosim
