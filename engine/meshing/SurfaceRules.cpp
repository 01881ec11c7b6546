#include "meshing/SurfaceRules.hpp"

#include <algorithm>

namespace orthosim {

RepairOptions repairOptions(SurfaceRole role) {
  RepairOptions o;
  if (role == SurfaceRole::Skin) {
    o.keepLargestOnly = true;
    o.planeCutLongestHole = true;
    o.maxPatchShare = 0.1;  // eyes, nostrils, an open mouth: each a few % of a face's skin at most
  } else {
    o.maxPatchShare = 0.25;  // a crop of the skull's vault or base
  }
  return o;
}

SurfaceReport repairAndCheck(SurfaceMesh& mesh, const std::string& name, SurfaceRole role) {
  SurfaceMesh work = mesh;
  SurfaceReport pre = checkSurface(work, name, SurfaceRequirement::OpenAllowed);
  RepairOptions options = repairOptions(role);
  options.knownSelfIntersections = pre.selfIntersections;
  const RepairReport repaired = repairSurface(work, name, options);
  if (repaired.repairs.empty()) {
    mesh = std::move(work);
    return pre;
  }
  SurfaceReport post = checkSurface(work, name, SurfaceRequirement::Closed);
  // What the first check accepted as open or crossing is repaired now: its warnings would mislead.
  std::vector<std::string> warnings;
  for (const std::string& w : pre.warnings)
    if (w.rfind(name + ": open:", 0) != 0 && w.rfind(name + ": self-intersecting:", 0) != 0) warnings.push_back(w);
  for (const std::string& w : repaired.lines(name)) warnings.push_back(w);
  warnings.insert(warnings.end(), post.warnings.begin(), post.warnings.end());
  post.warnings = std::move(warnings);
  mesh = std::move(work);
  return post;
}

}  // namespace orthosim
