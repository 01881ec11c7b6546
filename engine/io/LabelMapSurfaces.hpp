#pragma once
// Surfaces from a label map: a segmentation saved as one image whose voxels hold label
// numbers (3D Slicer's or ITK-SNAP's label map volume, NIfTI .nii/.nii.gz or NRRD .nrrd/.nhdr,
// raw or gzip-encoded). Each region (a set of labels) becomes a closed triangle surface through VTK:
// discrete flying edges on the region's mask, windowed-sinc smoothing, quadric decimation.
//
// Frame: millimetres in the patient frame of DICOM, LPS (+x the patient's left, +y posterior,
// +z superior), ITK's frame and the one in which 3D Slicer (4.11 on) saves models and markups.
// NIfTI's qform/sform world (RAS) and an NRRD "space" of right-anterior-superior are turned into
// it (x and y negated); an NRRD in left-posterior-superior is taken as it is. Voxel centres are at
// the image's physical points (origin + directions times index), so a region's surface lies half a
// voxel outside the centres of its outer voxels.
#include <Eigen/Core>
#include <stdexcept>
#include <string>
#include <vector>

#include "mesh/SurfaceMesh.hpp"

namespace orthosim {

// Anything wrong with a label map or the labels chosen; the message names the file and the defect.
struct LabelMapError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct LabelMap {
  std::string path;
  Eigen::Vector3i size = Eigen::Vector3i::Zero();            // voxels along i, j, k
  Eigen::Matrix3d directions = Eigen::Matrix3d::Identity();  // columns: the step of i, j, k in LPS mm
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();          // LPS mm of voxel (0, 0, 0)'s centre
  std::string orientation;  // where the placement came from, for the user ("NIfTI sform (RAS)", ...)
  std::vector<int> voxels;  // label per voxel, i fastest, then j, then k

  // The labels present (0, the background, excluded), ascending.
  std::vector<int> labels() const;
  Eigen::Vector3d spacing() const { return directions.colwise().norm().transpose(); }
  Eigen::Vector3d position(const Eigen::Vector3d& index) const { return origin + directions * index; }
};

// Reads .nii, .nii.gz, .nrrd or .nhdr (by extension, any case). Throws LabelMapError naming the
// file: missing or unreadable, another format, not 3-D, several components per voxel, values that
// are not whole numbers, a placement it cannot follow (an NRRD space other than LPS or RAS).
LabelMap readLabelMap(const std::string& path);

struct LabelRegion {
  std::string name;         // what it is, for messages ("skin", "skull", ...)
  std::vector<int> labels;  // the voxels with any of these labels
  // Only the region's outer boundary: voids enclosed by it (airways, sinuses, unlabelled pockets)
  // count as inside, so the surface is one envelope (the skin of the whole head).
  bool envelope = false;
};

struct LabelMapSurfaceOptions {
  int smoothingIterations = 20;  // windowed-sinc (vtkWindowedSincPolyDataFilter)
  double passBand = 0.05;        // its pass band: lower smooths more (VTK's range 0-2)
  int maxTriangles = 120000;     // per surface, by quadric decimation when the contour has more
};

// One closed, outward surface per region, in LPS mm (see above). Throws LabelMapError naming the
// file when a region has no labels, when one of its labels is not in the map (naming the label and
// the labels the map has), or when its surface comes out empty.
std::vector<SurfaceMesh> labelMapSurfaces(const LabelMap& map, const std::vector<LabelRegion>& regions,
                                          const LabelMapSurfaceOptions& options = {});

}  // namespace orthosim
