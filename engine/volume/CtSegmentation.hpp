#pragma once
// Automatic segmentation of a head CT or CBCT into what a case needs: the soft tissue's envelope
// (the skin), the skull with the maxilla and its teeth, the mandible with its teeth, and the air
// inside the face (airway, sinuses reached from it, a mouth with air) as cavities. Thresholds in
// grey values: Hounsfield units for CT; for CBCT, whose grey values are not calibrated, the bone's
// is taken from the histogram (two-class Otsu on the tissue's voxels).
//
// The work is done on a copy resampled to `voxelMm` (block averages, which also quiets noise); the
// result is a label map in the scan's LPS frame for io/LabelMapSurfaces.
#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "io/LabelMapSurfaces.hpp"
#include "volume/CtVolume.hpp"

namespace orthosim {

struct CtSegmentationOptions {
  double voxelMm = 1.0;                 // working voxel size: at least the scan's own
  std::optional<double> skinThreshold;  // air/tissue; default -400 HU, or from the histogram when not CT-like
  std::optional<double> boneThreshold;  // default 300 HU for CT, from the histogram otherwise
  // A surgeon's correction of the split: a point (LPS mm) on each bone. Without them the mandible
  // is the bone at the chin (lowest anterior bone) and the skull the bone at the top of the head.
  std::optional<Eigen::Vector3d> mandibleSeed, skullSeed;
  bool cavities = true;  // air inside the face as cavities
};

struct CtSegmentation {
  // Labels: 1 soft tissue, 2 skull (with the maxilla and its teeth), 3 mandible (with its teeth),
  // 4 air inside the face that becomes cavities (0: outside).
  LabelMap labels;
  static constexpr int kTissue = 1, kSkull = 2, kMandible = 3, kAir = 4;
  double skinThreshold = 0, boneThreshold = 0;  // the thresholds used, in the scan's grey values
  std::string thresholdSource;                  // "Hounsfield defaults", "given", "histogram (CBCT)"
  Eigen::Vector3d mandibleSeed = Eigen::Vector3d::Zero(), skullSeed = Eigen::Vector3d::Zero();  // used
  int splitErosions = 0;           // erosions needed to part the mandible from the skull
  double metalLevel = 0;           // grey value above which a voxel is metal (fillings, brackets)
  long metalVoxels = 0;            // voxels above it, for the user; they stay in the tooth they are in
  std::vector<std::string> notes;  // what was done and found, for the user
};

// Throws std::invalid_argument naming the option or what is missing (no tissue, no bone, the
// mandible not parted from the skull, a seed outside the bone).
CtSegmentation segmentCt(const CtVolume& volume, const CtSegmentationOptions& options = {});

}  // namespace orthosim
