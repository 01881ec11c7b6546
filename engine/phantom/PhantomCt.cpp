#include "phantom/PhantomCt.hpp"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "io/SurfaceImport.hpp"
#include "volume/SyntheticCt.hpp"

namespace orthosim {
namespace {
namespace fs = std::filesystem;

SurfaceMesh turned(SurfaceMesh m) {
  m.vertices = phantomToLps() * m.vertices;
  m.uv.resize(2, 0);
  return m;
}

// The landmarks file of the phantom's case ({hard: {...}, soft: {...}}) in LPS.
std::map<std::string, Eigen::Vector3d> landmarksIn(const fs::path& file, double mandibleRaise) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error(file.string() + ": cannot read the phantom's landmarks");
  const nlohmann::json j = nlohmann::json::parse(in);
  std::map<std::string, Eigen::Vector3d> out;
  for (const char* group : {"hard", "soft"})
    for (const auto& [name, p] : j.at(group).items()) out[name] = phantomToLps() * Eigen::Vector3d(p[0], p[1], p[2]);
  for (const char* name :
       {"lower_incisor_tip", "lower_incisor_apex", "lower_canine_left", "lower_canine_right", "lower_molar_left",
        "lower_molar_right", "menton", "pogonion", "gonion_left", "gonion_right", "mental_foramen_left",
        "mental_foramen_right", "condylion_left", "condylion_right", "lingula_left", "lingula_right"})
    if (out.count(name)) out[name].z() += mandibleRaise;
  return out;
}

CtVolume gridAround(const SurfaceMesh& skin, const PhantomScanOptions& o) {
  const Eigen::AlignedBox3d box = skin.boundingBox();
  const Eigen::Vector3d lo = box.min() - Eigen::Vector3d::Constant(6), hi = box.max() + Eigen::Vector3d::Constant(6);
  CtVolume grid;
  Eigen::Vector3d spacing = o.spacing;
  if (o.size) {
    grid.size = *o.size;
    spacing = (hi - lo).cwiseQuotient((grid.size - Eigen::Vector3i::Ones()).cast<double>());
  } else {
    grid.size = ((hi - lo).cwiseQuotient(spacing)).cast<int>() + Eigen::Vector3i::Ones();
  }
  grid.directions = spacing.asDiagonal();
  grid.origin = lo;
  return grid;
}

}  // namespace

Eigen::Matrix3d phantomToLps() {
  Eigen::Matrix3d r;
  r << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  return r;
}

PhantomCt phantomCt(const std::string& caseDir, const PhantomScanOptions& o) {
  const fs::path dir(caseDir);
  PhantomCt out;
  out.skin = turned(importSurface((dir / "skin.obj").string()));
  out.skull = turned(importSurface((dir / "skull.stl").string()));
  SurfaceMesh mandible = importSurface((dir / "mandible.stl").string());
  const double raise = o.occlusion ? kPhantomOcclusionRaiseMm : 0;
  mandible.vertices.row(2).array() += raise;
  out.mandible = turned(mandible);
  out.landmarks = landmarksIn(dir / "landmarks.json", raise);
  SyntheticCtInput in;
  in.grid = gridAround(out.skin, o);
  in.layers = {{&out.skin, 40.f}, {&out.skull, 1200.f}, {&out.mandible, 1200.f}};
  if (!o.occlusion) {
    out.cavity = turned(importSurface((dir / "oral_cavity.stl").string()));
    in.layers.insert(in.layers.begin() + 1, {&out.cavity, -1000.f});
  }
  in.noiseSigma = o.noiseSigma;
  in.seed = o.seed;
  if (o.metal) {
    MetalStreak m;
    m.at = out.landmarks.at("upper_molar_left") + Eigen::Vector3d(0, 0, 1.0);  // within the crown
    m.radiusMm = 1.2;
    m.towards = out.landmarks.at("upper_molar_right") - out.landmarks.at("upper_molar_left");
    in.metal.push_back(m);
  }
  out.ct = syntheticCt(in);
  return out;
}

}  // namespace orthosim
