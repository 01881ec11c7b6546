#pragma once
// A CT of the phantom, made as a scanner would see it: the phantom's case turned into the patient
// frame of DICOM (LPS: its anterior -x becomes -y, its right +y becomes -x), teeth in occlusion (the
// mandible raised 0.7 mm, as scans are taken), soft tissue 40 HU, bone 1200 HU, noise, partial
// volume, and a metal filling on the upper left first molar whose streak crosses the mouth.
#include <Eigen/Core>
#include <filesystem>

#include "mesh/SurfaceImport.hpp"
#include "mesh/SurfaceMesh.hpp"
#include "phantom/PhantomCase.hpp"
#include "scene/CaseFile.hpp"
#include "volume/SyntheticCt.hpp"

namespace orthosim::test {

// Phantom coordinates to LPS: a proper rotation about the superior axis.
inline Eigen::Matrix3d phantomToLps() {
  Eigen::Matrix3d r;
  r << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  return r;
}

constexpr double kOcclusionRaiseMm = 0.7;  // the phantom's teeth are 1.5 mm apart; a scan's less than 1

struct PhantomCt {
  SurfaceMesh skin, skull, mandible;  // LPS, the mandible in occlusion
  SurfaceMesh cavity;                 // the oral cavity, when scanned with air in the mouth
  Landmarks landmarks;                // LPS (the mandible's raised with it)
  CtVolume ct;
};

inline SurfaceMesh turned(SurfaceMesh m) {
  m.vertices = phantomToLps() * m.vertices;
  return m;
}

struct PhantomScan {
  Eigen::Vector3d spacing = Eigen::Vector3d(0.5, 0.5, 1.0);  // a head CT's: fine in-plane, thicker slices
  bool occlusion = true;  // the mandible raised into occlusion, no air in the mouth (lips closed)
  bool metal = true;
  unsigned seed = 7;
};

// The phantom case written to `phantomDir` (writePhantomCase) scanned as `how` says; without
// occlusion, as its case is: teeth 1.5 mm apart, its oral cavity air.
inline PhantomCt phantomCt(const std::filesystem::path& phantomDir, const PhantomScan& how = {}) {
  const Eigen::Vector3d& spacing = how.spacing;
  PhantomCt out;
  out.skin = turned(importSurface((phantomDir / "skin.obj").string()));
  out.skin.uv.resize(2, 0);
  out.skull = turned(importSurface((phantomDir / "skull.stl").string()));
  SurfaceMesh mandible = importSurface((phantomDir / "mandible.stl").string());
  if (how.occlusion) mandible.vertices.row(2).array() += kOcclusionRaiseMm;
  out.mandible = turned(mandible);
  const CaseSpec spec = loadCaseFile((phantomDir / "case.json").string());
  for (const auto& [name, p] : spec.landmarks) out.landmarks[name] = phantomToLps() * p;
  const double raise = how.occlusion ? kOcclusionRaiseMm : 0;  // the mandible's landmarks with it
  for (const char* name : {"lower_incisor_tip", "lower_incisor_apex", "lower_canine_left", "lower_canine_right",
                           "lower_molar_left", "lower_molar_right", "menton", "pogonion", "gonion_left", "gonion_right",
                           "mental_foramen_left", "mental_foramen_right", "condylion_left", "condylion_right"})
    if (out.landmarks.count(name)) out.landmarks[name].z() += raise;
  SyntheticCtInput in;
  const Eigen::AlignedBox3d box = out.skin.boundingBox();
  const Eigen::Vector3d lo = box.min() - Eigen::Vector3d::Constant(6), hi = box.max() + Eigen::Vector3d::Constant(6);
  in.grid.origin = lo;
  in.grid.directions = spacing.asDiagonal();
  in.grid.size = ((hi - lo).cwiseQuotient(spacing)).cast<int>() + Eigen::Vector3i::Ones();
  in.layers = {{&out.skin, 40.f}, {&out.skull, 1200.f}, {&out.mandible, 1200.f}};
  if (!how.occlusion) {
    out.cavity = turned(importSurface((phantomDir / "oral_cavity.stl").string()));
    in.layers.insert(in.layers.begin() + 1, {&out.cavity, -1000.f});
  }
  in.noiseSigma = 25;
  in.seed = how.seed;
  if (how.metal) {
    MetalStreak m;
    m.at = out.landmarks.at("upper_molar_left") + Eigen::Vector3d(0, 0, 1.0);  // within the crown
    m.radiusMm = 1.2;
    m.towards = out.landmarks.at("upper_molar_right") - out.landmarks.at("upper_molar_left");
    in.metal.push_back(m);
  }
  out.ct = syntheticCt(in);
  return out;
}

}  // namespace orthosim::test
