#pragma once
// The lips' inner surface bonded instead of sliding (a parameter of the prediction band): a variant of a scene with
// contact in which the contact nodes that touch a bone at rest are bonded to the fragment whose
// surface they touch, as if the mucosa stuck to the teeth and gums. "Touch" is a distance: a node
// within `touchDistance` mm of a contact surface at rest. The nodes further away keep sliding.
#include <vector>

#include "scene/Scene.hpp"

namespace orthosim {

struct BondedContactReport {
  int contactNodes = 0;               // distinct contact nodes before
  int bonded = 0;                     // of which bonded to a fragment
  std::vector<double> restDistances;  // every contact node's distance to its nearest contact surface (mm)
};

// Rest distance of every distinct contact node to the nearest contact surface (any fragment's),
// in the order of the nodes' first appearance; and which surface (index into scene.contacts).
struct ContactGaps {
  std::vector<int> nodes;
  std::vector<double> distance;
  std::vector<int> contact;
};
ContactGaps contactGaps(const Scene& scene);

// Bonds the contact nodes within touchDistance of a contact surface at rest to that surface's
// fragment (the nearest surface when several are in reach) and takes them out of every contact.
// Contacts left with no node are removed. Throws std::invalid_argument for a contact surface that
// moves with no fragment (fixed in space: there is nothing to bond to) or a bad distance.
BondedContactReport bondTouchingContactNodes(Scene& scene, double touchDistance);

}  // namespace orthosim
