#pragma once
// Label maps written for the tests, as a segmentation tool would save them: NIfTI through VTK's
// writer, NRRD (raw or gzip-encoded) by hand. In a library of its own (tests/CMakeLists.txt), so
// VTK's headers reach only LabelMapFiles.cpp.
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace orthosim::test {

// A regular grid of voxel centres, origin + spacing * (i, j, k) in LPS mm; the label of voxel
// (i, j, k) at i + n.x * (j + n.y * k).
struct LabelGrid {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  double spacing = 1;
  Eigen::Vector3i n = Eigen::Vector3i::Zero();
  std::vector<std::uint8_t> labels;
};

// NIfTI (.nii or .nii.gz) with a qform from VTK's data coordinates to RAS (x and y negated, so the
// grid's coordinates are LPS). Throws std::runtime_error when the file is not written.
void writeNiftiLabels(const LabelGrid& grid, const std::string& path);
// NRRD with `space` (left-posterior-superior, right-anterior-superior, ...) taking the grid's
// coordinates as they are, its voxels raw or gzip-encoded; a .nhdr path gets a detached header and
// the voxels in <stem>.raw beside it. `directions` (columns: the steps of i, j, k), when given,
// replace spacing times the identity: an oblique grid.
void writeNrrdLabels(const LabelGrid& grid, const std::string& path, bool gzip,
                     const std::string& space = "left-posterior-superior", const Eigen::Matrix3d* directions = nullptr);
// A float NIfTI image with fractional values (an intensity image, not a label map).
void writeNiftiIntensities(const std::string& path);

}  // namespace orthosim::test
