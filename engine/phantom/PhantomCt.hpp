#pragma once
// The phantom as a CT scanner would see it, for trying the scan import without patient data and for
// the tests and benchmark of that import: the phantom's case turned into the patient frame of DICOM
// (LPS: its anterior -x becomes -y, its right +y becomes -x), soft tissue 40 HU, bone 1200 HU,
// noise, partial volume, and a metal filling in the upper left first molar whose streak crosses the
// mouth. As scans are taken, the teeth are in occlusion (the mandible raised 0.7 mm) and the lips
// closed over a mouth without air; or, as the phantom's case is, apart with its oral cavity air.
#include <Eigen/Core>
#include <map>
#include <optional>
#include <string>

#include "mesh/SurfaceMesh.hpp"
#include "volume/CtVolume.hpp"

namespace orthosim {

// Phantom coordinates to LPS: a proper rotation about the superior axis.
Eigen::Matrix3d phantomToLps();

constexpr double kPhantomOcclusionRaiseMm = 0.7;  // the phantom's teeth are 1.5 mm apart; a scan's less than 1

struct PhantomScanOptions {
  Eigen::Vector3d spacing = Eigen::Vector3d(0.5, 0.5, 1.0);  // a head CT's: fine in-plane, thicker slices
  // A grid of this many voxels centred on the head instead (spacing then from the head's extent).
  std::optional<Eigen::Vector3i> size;
  bool occlusion = true;
  bool metal = true;
  float noiseSigma = 25;
  unsigned seed = 7;
};

struct PhantomCt {
  SurfaceMesh skin, skull, mandible;                 // LPS, the mandible as scanned
  SurfaceMesh cavity;                                // the oral cavity, when scanned with air in the mouth
  std::map<std::string, Eigen::Vector3d> landmarks;  // LPS, the mandible's moved with it
  CtVolume ct;
};

// The phantom case written at `caseDir` (phantom/PhantomCase.hpp: writePhantomCase) scanned as
// `options` says.
PhantomCt phantomCt(const std::string& caseDir, const PhantomScanOptions& options = {});

}  // namespace orthosim
