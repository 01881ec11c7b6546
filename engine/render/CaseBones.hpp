#pragma once
// A case's bones as the renderer draws them: each bone surface cut into the fragments its
// osteotomies make (each triangle goes to the fragment its centroid lies in, as for contact), so
// every piece can be drawn at its fragment's pose.
#include <string>
#include <vector>

#include "mesh/SurfaceMesh.hpp"
#include "scene/CaseModel.hpp"

namespace orthosim::render {

struct BonePiece {
  std::string fragment;   // fragment name (CaseModel::coupling.fragments)
  int fragmentIndex = 0;  // its index there, and in a solve's SimState::fragments
  bool fixed = false;     // part of a bone that the case holds in place
  SurfaceMesh surface;    // at rest, only the piece's own vertices
};

// Reads the case's bone surfaces and splits them. Throws SceneError naming a bone whose surface
// cannot be read.
std::vector<BonePiece> caseBonePieces(const CaseModel& model);

}  // namespace orthosim::render
