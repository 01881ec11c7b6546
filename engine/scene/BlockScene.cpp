#include "scene/BlockScene.hpp"

#include "math/Angles.hpp"
#include "meshing/BoxMesh.hpp"

namespace orthosim {

FragmentMotion blockReferenceMotion() {
  FragmentMotion m;
  m.translation = {0, 5, 3};
  m.rotation = {0, 0, 5.0 * kPi / 180.0};
  m.center = {45, 20, 0};
  return m;
}

Scene makeBlockScene(const Eigen::Vector3i& cells) {
  Scene s;
  s.mesh = makeBoxMesh({Eigen::Vector3d(60, 40, 20), cells});
  FragmentSpec a{"A", {}, false}, b{"B", {}, false};
  for (int i = 0; i < s.mesh.numNodes(); ++i) {
    if (s.mesh.rest(2, i) != 0.0) continue;
    (s.mesh.rest(0, i) < 30.0 ? a : b).nodes.push_back(i);
  }
  s.fragments = {a, b};
  s.plan["B"] = blockReferenceMotion();
  return s;
}

}  // namespace orthosim
