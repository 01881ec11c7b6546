#pragma once
// A cube of side L on rollers at z = 0 (a frictionless support: z held, one corner pinned, the next
// corner along x held in y and z so that it cannot spin) with the nodes of its top face: the
// tissue the contact tests press a rigid plate onto.
#include <vector>

#include "meshing/BoxMesh.hpp"
#include "scene/Scene.hpp"

namespace orthosim::test {

struct CubeOnRollers {
  Scene scene;
  std::vector<int> top;  // nodes on z = L
};

inline CubeOnRollers cubeOnRollers(double L, int cells) {
  CubeOnRollers c;
  Scene& s = c.scene;
  s.mesh = makeBoxMesh({Eigen::Vector3d(L, L, L), Eigen::Vector3i(cells, cells, cells)});
  FixedSpec rollers, pin, noSpin;
  rollers.components = {false, false, true};
  noSpin.components = {false, true, true};
  for (int i = 0; i < s.mesh.numNodes(); ++i) {
    const Eigen::Vector3d X = s.mesh.rest.col(i);
    if (X.z() == L) c.top.push_back(i);
    if (X.z() != 0) continue;
    if (X.x() == 0 && X.y() == 0)
      pin.nodes.push_back(i);
    else if (X.x() == L && X.y() == 0)
      noSpin.nodes.push_back(i);
    else
      rollers.nodes.push_back(i);
  }
  s.fixed = {rollers, pin, noSpin};
  return c;
}

}  // namespace orthosim::test
