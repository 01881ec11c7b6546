#include "solver/PinchedTissue.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cstdio>
#include <map>

#include "mesh/MeshQuality.hpp"
#include "solver/Model.hpp"
#include "solver/SimState.hpp"

namespace orthosim {
namespace {

// The fragments a constrained node follows (several when blended near a cut), or "fixed".
void addFollowed(const Model& model, int node, std::vector<std::string>& names) {
  const Coupling& c = model.coupling();
  if (!c.isSkinned(node)) names.push_back("fixed");
  for (const Coupling::SkinTerm* t = c.skinBegin(node); t != c.skinEnd(node); ++t)
    if (t->weight > 1e-6) names.push_back(model.scene().fragments[t->fragment].name);
}

}  // namespace

std::vector<PinchedTissue> findPinchedTissue(const Model& model, const Eigen::Matrix3Xd& x, double maxDetF) {
  const TetMesh& mesh = model.scene().mesh;
  std::vector<bool> active(mesh.numTets(), false);
  for (int e : model.energy().activeElements()) active[e] = true;
  std::map<std::vector<std::string>, PinchedTissue> groups;
  for (int e = 0; e < mesh.numTets(); ++e) {
    if (active[e]) continue;
    const double det = model.energy().deformationGradient(e, x).determinant();
    if (!(det < maxDetF)) continue;
    std::vector<std::string> names;
    for (int a = 0; a < 4; ++a) addFollowed(model, mesh.tets(a, e), names);
    std::sort(names.begin(), names.end());
    names.erase(std::unique(names.begin(), names.end()), names.end());
    PinchedTissue& p = groups[names];
    p.fragments = names;
    p.threshold = maxDetF;
    ++p.elements;
    if (det <= 0) ++p.inverted;
    const auto angles = dihedralAnglesDeg(mesh, e);
    if (*std::min_element(angles.begin(), angles.end()) < kSliverDeg) ++p.slivers;
    p.minDetF = std::min(p.minDetF, det);
    for (int a = 0; a < 4; ++a) p.center += mesh.rest.col(mesh.tets(a, e)) / 4.0;  // summed, divided below
  }
  std::vector<PinchedTissue> out;
  for (auto& [names, p] : groups) {
    p.center /= p.elements;
    out.push_back(std::move(p));
  }
  std::sort(out.begin(), out.end(),
            [](const PinchedTissue& a, const PinchedTissue& b) { return a.minDetF < b.minDetF; });
  return out;
}

std::vector<PinchedTissue> findPinchedByPlan(const Model& model, const SimState& start, const PlanTargets& targets,
                                             double maxDetF) {
  SimState end = start;
  model.coupling().applyBoundary(targets.boundary, end);
  return findPinchedTissue(model, end.x, maxDetF);
}

std::vector<std::string> pinchedByPlanWarnings(const Model& model, const std::map<std::string, FragmentMotion>& plan) {
  const SimState rest = model.restState();
  std::vector<std::string> out;
  for (const PinchedTissue& p : findPinchedByPlan(model, rest, model.targetsFromPlan(plan, rest)))
    out.push_back(describePinchedTissue(p, model.scene().landmarks));
  return out;
}

std::string describePinchedTissue(const PinchedTissue& p, const std::map<std::string, Eigen::Vector3d>& landmarks) {
  std::string names;
  for (size_t i = 0; i < p.fragments.size(); ++i)
    names += (i == 0 ? "" : i + 1 == p.fragments.size() ? " and " : ", ") + p.fragments[i];
  char figures[160];
  std::snprintf(figures, sizeof figures, "%d tetrahedra below %.3g of their volume, %d inverted, min det F %.3g",
                p.elements, p.threshold, p.inverted, p.minDetF);
  char where[160];
  std::snprintf(where, sizeof where, " around (%.1f, %.1f, %.1f) mm", p.center.x(), p.center.y(), p.center.z());
  std::string text = "tissue moved only by " + names + " is crushed by the plan (" + figures + ")" + where;
  const std::string* nearest = nullptr;
  double best = 0;
  for (const auto& [name, at] : landmarks)
    if (!nearest || (at - p.center).norm() < best) nearest = &name, best = (at - p.center).norm();
  if (nearest) {
    std::snprintf(where, sizeof where, "%.1f mm from ", best);
    text += ", " + std::string(where) + *nearest;
  }
  if (p.slivers == p.elements)
    return text + ": " + (p.elements == 1 ? "it is a sliver" : "all are slivers") +
           " of the mesh (flat at rest), which a small difference between the pieces turns over; the rest of the "
           "tissue is solved, a better mesh there removes it";
  if (p.slivers > 0) text += ", " + std::to_string(p.slivers) + " of them slivers of the mesh (flat at rest)";
  return text +
         ": the pieces move into each other there, or turn too differently for the blend across their cut; "
         "check the bone positions";
}

}  // namespace orthosim
