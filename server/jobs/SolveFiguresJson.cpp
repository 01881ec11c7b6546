#include "jobs/SolveFiguresJson.hpp"

#include <algorithm>
#include <cmath>

#include "eval/ResultJson.hpp"

namespace orthosim::server {
using nlohmann::json;
namespace {

json anatomical(const Eigen::Vector3d& d, const AnatomicalFrame& f) {
  return {{"anterior_mm", d.dot(f.anterior)},
          {"superior_mm", d.dot(f.superior)},
          {"right_mm", d.dot(f.right)},
          {"total_mm", d.norm()}};
}

}  // namespace

json solveFiguresJson(const CaseModel& model, const SkinFigureProbe& probe, const SolveResult& r,
                      const AnatomicalFrame& frame) {
  const SkinFigures skin = probe.figures(model, r.state.x);
  json landmarks = json::object();
  for (const LandmarkMotion& l : skin.landmarks) landmarks[l.name] = anatomical(l.displacement, frame);
  json out = solveOutcomeJson(r);  // converged, error, load_fraction, residual_n: as in result.json
  out.update({{"solve_s", r.timings.total},
              {"iterations", r.iterations},
              {"substeps", static_cast<int>(r.substeps.size())},
              {"max_skin_displacement_mm", skin.maxDisplacementMm},
              {"max_skin_displacement_at_mm", {skin.maxAt.x(), skin.maxAt.y(), skin.maxAt.z()}},
              {"mean_skin_displacement_mm", skin.meanDisplacementMm},
              {"landmarks", std::move(landmarks)},
              {"resolution", resolutionName(model.resolution)},
              {"nodes", model.scene.mesh.numNodes()},
              {"tetrahedra", model.scene.mesh.numTets()},
              {"warnings", r.warnings}});
  return out;
}

json skinDifferenceJson(const CaseModel& coarse, const Eigen::Matrix3Xd& coarseX, const CaseModel& fine,
                        const Eigen::Matrix3Xd& fineX) {
  if (coarse.skinEmbedding.numPoints() == 0 || coarse.skinEmbedding.numPoints() != fine.skinEmbedding.numPoints())
    return json::object();
  const Eigen::VectorXd d =
      (coarse.skinEmbedding.apply(coarseX) - fine.skinEmbedding.apply(fineX)).colwise().norm().transpose();
  std::vector<double> sorted(d.data(), d.data() + d.size());
  std::sort(sorted.begin(), sorted.end());
  const double p95 =
      sorted[std::min(sorted.size() - 1, static_cast<size_t>(0.95 * static_cast<double>(sorted.size())))];
  return {{"max_mm", d.maxCoeff()}, {"mean_mm", d.mean()}, {"p95_mm", p95}};
}

}  // namespace orthosim::server
