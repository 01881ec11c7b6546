#pragma once
// A case at one resolution, ready to solve: the Scene (fragments from the bones and osteotomies,
// blended couplings near the cuts, the plan) and the full-resolution skin embedded in the tissue.
// Data flows one way: CaseSpec -> CaseTissue -> CaseModel -> Model (solver).
#include <string>
#include <vector>

#include "mesh/PointEmbedding.hpp"
#include "scene/BoneFragments.hpp"
#include "scene/CaseFile.hpp"
#include "scene/CaseTissue.hpp"
#include "scene/Scene.hpp"

namespace orthosim {

struct CaseModel {
  CaseSpec spec;
  Resolution resolution = Resolution::Coarse;
  CaseTissue tissue;
  FragmentCoupling coupling;  // fragment names and groups, as in scene.fragments
  Scene scene;
  PointEmbedding skinEmbedding;  // tissue.skin's vertices in the tetrahedra (empty without a skin)
  std::vector<std::string> warnings;

  // The skin at full resolution for deformed node positions x (3 x nodes); the rest skin for
  // x = rest. Empty when the case has no skin.
  SurfaceMesh deformedSkin(const Eigen::Matrix3Xd& x) const;
};

// Builds the scene of `spec` on `tissue` (bone groups split by the cuts, fixed bones held, volume
// node sets fixed except where a bone group claims the node). Throws SceneError.
Scene caseScene(const CaseSpec& spec, const CaseTissue& tissue, FragmentCoupling* coupling = nullptr);

// Everything: tissue (cached when options.cacheDir is set), scene, skin embedding.
CaseModel buildCaseModel(const CaseSpec& spec, Resolution resolution, const CaseTissueOptions& options = {});

}  // namespace orthosim
