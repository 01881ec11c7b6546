#pragma once
// A small stand-in for the head, from primitives, shared by the tissue-mesh tests: a spherical
// skin envelope (radius 50 mm) whose uv is an affine function of position (so interpolation must
// reproduce it exactly), a spherical bone wholly inside, a spherical bone poking out through the
// top, and a thin flat ellipsoid cavity that crosses the skin and cuts into the poking bone. All
// smooth, as anatomy is; boxes (sharp corners, long flat seams) are the hard case, tested apart.
#include <Eigen/Core>
#include <vector>

#include "mesh/SurfaceMesh.hpp"
#include "meshing/SurfacePrimitives.hpp"

namespace orthosim::test {

inline Eigen::Vector2d affineUv(const Eigen::Vector3d& x) {
  return {0.3 + 0.01 * x.x() + 0.02 * x.y() - 0.003 * x.z(), 0.5 + 0.005 * x.x() - 0.015 * x.z()};
}

inline SurfaceMesh envelope(int levels) {
  SurfaceMesh s = makeIcosphere(50, levels);
  for (int i = 0; i < s.numVertices(); ++i) s.uv.col(i) = affineUv(s.vertices.col(i));
  return s;
}

struct TissueScene {
  SurfaceMesh skin;
  std::vector<SurfaceMesh> solids;  // inner bone, poking bone, cavity
  std::vector<std::string> names{"inner bone", "poking bone", "cavity"};
};

inline TissueScene tissueScene(int envelopeLevels = 4, int boneLevels = 3) {
  TissueScene s;
  s.skin = envelope(envelopeLevels);
  SurfaceMesh inner = makeIcosphere(15, boneLevels, Eigen::Vector3d(-15, 0.5, -12));
  inner.uv.resize(2, 0);
  SurfaceMesh poking = makeIcosphere(20, boneLevels, Eigen::Vector3d(20, 0.5, 50));
  SurfaceMesh cavity = makeIcosphere(1, boneLevels);
  for (int i = 0; i < cavity.numVertices(); ++i)
    cavity.vertices.col(i) =
        Eigen::Vector3d(35, 0.3, 29) + Eigen::Vector3d(35, 18, 4).cwiseProduct(cavity.vertices.col(i));
  poking.uv.resize(2, 0);
  cavity.uv.resize(2, 0);
  s.solids = {inner, poking, cavity};
  return s;
}

}  // namespace orthosim::test
