// No flat tetrahedra between nodes that all follow one bone. On variant 3's
// fine mesh TetGen (surface kept, -Y) left 75 tetrahedra with all four nodes on one bone below 5
// degrees, down to 0.21, on the mandible's interface where the right sagittal split's blend runs;
// a few tenths of a millimetre of blend turned them over, their free neighbours had to pass
// through them, and cohort patient M9's fine solve took 23 substeps with tissue "crushed by the
// plan" (min det F -1.44, a free node dragged 14 mm). They are now removed by a free node each
// (meshing/InterfaceSlivers, scene/SurfaceTissue).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <regex>

#include "eval/Cohort.hpp"
#include "mesh/MeshQuality.hpp"
#include "scene/CaseModel.hpp"
#include "solver/Model.hpp"
#include "solver/PinchedTissue.hpp"
#include "solver/PlanSolver.hpp"

namespace fs = std::filesystem;

namespace orthosim {
namespace {

TEST(BoneInterface, VariantThreeFineKeepsFewFlatTetsOnOneBoneAndM9SolvesInOneSubstep) {
  const fs::path dir = fs::temp_directory_path() / ("orthosim_bone_interface_" + std::to_string(::getpid()));
  const auto& cohort = cohortPatients();
  const auto m9 = std::find_if(cohort.begin(), cohort.end(), [](const CohortPatient& p) { return p.id == "M9"; });
  ASSERT_NE(m9, cohort.end());
  ASSERT_EQ(m9->variant, 3);
  const CaseSpec spec = loadCaseFile(writeCohortCase(*m9, (dir / "case").string()));
  const CaseModel m = buildCaseModel(spec, Resolution::Fine, {(dir / "cache").string()});
  const TetMesh& mesh = m.scene.mesh;

  // Tetrahedra whose four nodes lie on one bone and which are flatter than 5 degrees: TetGen leaves
  // about 75 (down to 0.21 deg); the removal must take out at least four in five, and the mesh must
  // hold what its report says is left. On its own branch it left 3 (4.5-4.9 deg); since the skin
  // and cavity edges are split as well (meshing/LongEdgeSplit) TetGen returns a degenerate element
  // under the bolder clean-up, the milder one is used, and 11 are left, down to 0.21 deg: open.
  int flat = 0, onOneBone = 0;
  double worst = 180;
  for (const std::vector<int>& bone : m.tissue.boneNodes) {
    std::vector<char> on(mesh.numNodes(), 0);
    for (int n : bone) on[n] = 1;
    for (int e = 0; e < mesh.numTets(); ++e) {
      if (!(on[mesh.tets(0, e)] && on[mesh.tets(1, e)] && on[mesh.tets(2, e)] && on[mesh.tets(3, e)])) continue;
      ++onOneBone;
      const auto angles = dihedralAnglesDeg(mesh, e);
      const double smallest = *std::min_element(angles.begin(), angles.end());
      worst = std::min(worst, smallest);
      flat += smallest < 5.0;
    }
  }
  int found = -1, left = -1;
  for (const std::string& line : m.tissue.report) {
    std::smatch match;
    if (std::regex_search(line, match,
                          std::regex("(\\d+) flat tetrahedra on one bone removed by \\d+ new nodes.*?, (\\d+) left")))
      found = std::stoi(match[1]), left = std::stoi(match[2]);
  }
  std::cout << "variant 3, fine: " << mesh.numNodes() << " nodes, " << mesh.numTets() << " tets, " << onOneBone
            << " with all nodes on one bone, " << flat << " of them below 5 deg (TetGen left " << found
            << "), min dihedral " << worst << " deg\n";
  EXPECT_GT(onOneBone, 0);
  ASSERT_GT(found, 0) << "the mesher's report does not say how many flat tetrahedra it removed";
  EXPECT_EQ(flat, left);
  EXPECT_LE(5 * left, found);

  // M9's plan (the mandible turned 3 degrees about a condyle, split on both sides): one substep,
  // nothing crushed or turned over, no node farther than the bone moves.
  Model model(m.scene);
  const SolveResult r = solveScene(model);
  ASSERT_TRUE(r.converged) << r.error;
  EXPECT_EQ(r.substeps.size(), 1u);
  EXPECT_EQ(r.refinements, 0);
  for (const std::string& w : r.warnings) ADD_FAILURE() << "warning: " << w;
  EXPECT_TRUE(findPinchedTissue(model, r.state.x).empty());
  double minDet = 1e300;
  for (int e = 0; e < mesh.numTets(); ++e)
    minDet = std::min(minDet, model.energy().deformationGradient(e, r.state.x).determinant());
  EXPECT_GT(minDet, 0.0);
  const double moved = (r.state.x - mesh.rest).colwise().norm().maxCoeff();
  std::cout << "M9 fine: " << r.iterations << " Newton iterations, " << r.substeps.size() << " substep(s), "
            << r.timings.total << " s; min det F " << minDet << ", largest node motion " << moved << " mm\n";
  EXPECT_LT(moved, 7.0);  // the mandible moves 6.4 mm at most; a node dragged through a sliver went 14
  fs::remove_all(dir);
}

}  // namespace
}  // namespace orthosim
