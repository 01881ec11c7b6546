#include "eval/RealFace.hpp"

#include <fstream>
#include <limits>
#include <stdexcept>
#include <utility>

#include "scene/CaseModel.hpp"
#include "solver/PlanSolver.hpp"

namespace orthosim {
namespace fs = std::filesystem;
using nlohmann::json;

json realFaceCaseJson(const fs::path& face, const json& plan) {
  const auto f = [&](const char* name) { return (face / name).string(); };
  return {{"name", "artisynth face"},
          {"frame", {{"anterior", {-1, 0, 0}}, {"superior", {0, 0, 1}}, {"right", {0, 1, 0}}}},
          {"tissue", {{"node", f("face_volume.node")}, {"ele", f("face_volume.ele")}, {"skin", f("face_surface.obj")}}},
          {"bones",
           {{{"name", "midface"},
             {"surface", f("maxilla.obj")},
             {"nodes", f("fixed_to_skull.txt")},
             {"derive", true},
             {"candidates", f("deep_surface.txt")},
             {"bond_distance_mm", 2.0},
             {"fixed", true}},
            {{"name", "mandible"}, {"surface", f("mandible.obj")}, {"nodes", f("attached_to_mandible.txt")}}}},
          // Read off the bones and the skin (cases/artisynth_face): the maxilla's incisor tip at z
          // 99 mm, so its apex about 23 mm above; the palate's back end; the upper and lower first
          // molars (tops of the crowns); gonion, the most posterior-inferior point of each angle.
          // Soft tissue: the most anterior midline skin point of each height band (see
          // anteriorMostMidlineVertex) and, for the stomion, the front of the lips' contact line.
          {"landmarks",
           {{"hard",
             {{"upper_incisor_apex", {52, 0, 122}},
              {"PNS", {106.5, 0, 123.6}},
              {"upper_molar_left", {80, -25, 103}},
              {"upper_molar_right", {80, 25, 103}},
              {"lower_molar_left", {81.9, -23.7, 99.1}},
              {"lower_molar_right", {81.9, 23.7, 99.1}},
              {"gonion_left", {134.3, -46.6, 78.9}},
              {"gonion_right", {134.3, 46.6, 78.9}}}},
            {"soft",
             {{"pronasale", {20.5, 0, 138.3}},
              {"subnasale", {32.6, 0, 123.3}},
              {"labrale_superius", {37.4, 0, 101.6}},
              {"stomion", {41.1, 0, 97.5}},
              {"labrale_inferius", {42.3, 0, 88.0}},
              {"soft_pogonion", {48.3, 0, 63.1}}}}}},
          {"cuts", {{{"template", "le_fort_1"}, {"bone", "midface"}}, {{"template", "bsso"}, {"bone", "mandible"}}}},
          // Lips and cheeks slide on the teeth of both jaws.
          {"contact", {{{"bones", {"midface", "mandible"}}, {"range_mm", 15}}}},
          {"plan", plan}};
}

int anteriorMostMidlineVertex(const SurfaceMesh& skin, double zLo, double zHi) {
  int best = -1;
  for (int i = 0; i < skin.numVertices(); ++i) {
    const Eigen::Vector3d p = skin.vertices.col(i);
    if (std::abs(p.y()) > 4 || p.z() < zLo || p.z() > zHi) continue;
    if (best < 0 || p.x() < skin.vertices(0, best)) best = i;
  }
  return best;
}

namespace {

// The two ratios of one plan: upper lip and nose tip for the Le Fort I advancement, chin and lower
// lip for the mandibular setback (in that order).
std::vector<MovementRatio> realFacePlanRatios(const fs::path& face, const fs::path& work, bool maxilla) {
  const Eigen::Vector3d h = maxilla ? Eigen::Vector3d(-5, 0, 0) : Eigen::Vector3d(5, 0, 0);
  const json plan = {{maxilla ? "maxilla" : "mandible", {{"translation_mm", {h.x(), h.y(), h.z()}}}}};
  const fs::path file = work / (maxilla ? "face_le_fort_1.json" : "face_setback.json");
  std::ofstream(file) << realFaceCaseJson(face, plan).dump(2);
  const CaseModel m = buildCaseModel(loadCaseFile(file.string()), Resolution::Coarse);
  Model model(m.scene);
  const SolveResult r = solveScene(model);
  if (!r.converged) throw std::runtime_error("real face: the solve did not converge: " + r.error);
  const SurfaceMesh rest = m.deformedSkin(m.scene.mesh.rest), moved = m.deformedSkin(r.state.x);
  const int nose = anteriorMostMidlineVertex(rest, 0, 1e9);
  // Bands in the order of ratioBands(): chin, lower lip (setback); upper lip, nose (advancement).
  const std::vector<std::pair<size_t, int>> picks =
      maxilla ? std::vector<std::pair<size_t, int>>{{2, anteriorMostMidlineVertex(rest, 95, 112)}, {3, nose}}
              : std::vector<std::pair<size_t, int>>{{0, anteriorMostMidlineVertex(rest, 54, 70)},
                                                    {1, anteriorMostMidlineVertex(rest, 80, 91)}};
  std::vector<MovementRatio> out;
  for (const auto& [k, v] : picks) {
    MovementRatio mr;
    if (v < 0) {
      mr.band = ratioBands()[k];
      mr.ratio = std::numeric_limits<double>::quiet_NaN();
      mr.note = "no midline skin vertex in the landmark's height band";
    } else {
      mr = movementRatio(ratioBands()[k], moved.vertices.col(v) - rest.vertices.col(v), h, Eigen::Vector3d(-1, 0, 0));
    }
    out.push_back(mr);
  }
  return out;
}

}  // namespace

std::vector<MovementRatio> realFaceRatios(const fs::path& face, const fs::path& work) {
  fs::create_directories(work);
  const std::vector<MovementRatio> advancement = realFacePlanRatios(face, work, true);
  const std::vector<MovementRatio> setback = realFacePlanRatios(face, work, false);
  // Back to the bands' order: chin, lower lip, upper lip, nose.
  return {setback[0], setback[1], advancement[0], advancement[1]};
}

}  // namespace orthosim
