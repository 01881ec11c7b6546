#include "scene/CaseModel.hpp"

#include <set>
#include <sstream>

#include "scene/SceneFields.hpp"

namespace orthosim {

Scene caseScene(const CaseSpec& spec, const CaseTissue& tissue, FragmentCoupling* couplingOut) {
  if (tissue.boneNodes.size() != spec.bones.size())
    throw SceneError(spec.file + ": the tissue has bonded groups for " + std::to_string(tissue.boneNodes.size()) +
                     " bones, the case lists " + std::to_string(spec.bones.size()));
  Scene scene;
  scene.mesh = tissue.mesh;
  scene.indexBase = tissue.indexBase;
  scene.youngsModulus = spec.youngsModulus;
  scene.poissonRatio = spec.poissonRatio;
  scene.solver = spec.solver;
  scene.plan = spec.plan;

  std::vector<BoneGroup> groups;
  for (size_t b = 0; b < spec.bones.size(); ++b) groups.push_back({spec.bones[b].name, tissue.boneNodes[b]});
  FragmentCoupling coupling;
  try {
    coupling = splitBoneGroups(scene.mesh.rest, groups, spec.regions, spec.blendWidth);
  } catch (const std::invalid_argument& e) {
    throw SceneError(spec.file + ": cuts: " + e.what());
  }
  std::set<int> coupled;
  for (size_t f = 0; f < coupling.fragments.size(); ++f) {
    scene.fragments.push_back({coupling.fragments[f], coupling.nodes[f], false});
    coupled.insert(coupling.nodes[f].begin(), coupling.nodes[f].end());
  }
  scene.blended = coupling.blended;
  for (const BlendedNode& b : scene.blended) coupled.insert(b.node);

  // Volume cases: extra held node sets; a node a bone group claims follows the bone instead (the
  // ArtiSynth face fixes its whole deep surface, maxilla included).
  for (size_t k = 0; k < spec.fixed.size(); ++k) {
    FixedSpec fixed;
    fixed.components = spec.fixed[k].components;
    for (int i : readNodeSet(spec.fixed[k].nodes, scene.mesh.numNodes(), "fixed[" + std::to_string(k) + "].nodes"))
      if (!coupled.count(i)) fixed.nodes.push_back(i);
    scene.fixed.push_back(std::move(fixed));
  }
  if (couplingOut) *couplingOut = std::move(coupling);
  return scene;
}

SurfaceMesh CaseModel::deformedSkin(const Eigen::Matrix3Xd& x) const {
  SurfaceMesh out = tissue.skin;
  if (out.numVertices() > 0) out.vertices = skinEmbedding.apply(x);
  return out;
}

CaseModel buildCaseModel(const CaseSpec& spec, Resolution resolution, const CaseTissueOptions& options) {
  CaseModel m;
  m.spec = spec;
  m.resolution = resolution;
  m.tissue = buildCaseTissue(spec, resolution, options);
  m.scene = caseScene(spec, m.tissue, &m.coupling);
  for (size_t f = 0; f < m.coupling.fragments.size(); ++f) {
    if (!m.coupling.nodes[f].empty()) continue;
    bool blended = false;
    for (const BlendedNode& b : m.coupling.blended)
      for (const auto& [frag, w] : b.weights) blended = blended || frag == static_cast<int>(f);
    if (!blended) m.warnings.push_back("fragment '" + m.coupling.fragments[f] + "' has no tissue bonded to it");
  }
  if (m.tissue.skin.numVertices() > 0) {
    try {
      m.skinEmbedding = embedPoints(m.tissue.mesh, m.tissue.skin.vertices);
    } catch (const std::exception& e) {
      throw SceneError(spec.file + ": tissue.skin: " + e.what());
    }
    // Surface files store single precision, and a simplified tissue cuts corners of a curved skin:
    // only distances that show on screen are worth a warning.
    if (m.skinEmbedding.maxOutsideDistance() > 0.5) {
      std::ostringstream s;
      s << "skin: " << m.skinEmbedding.numOutside() << " of " << m.skinEmbedding.numPoints()
        << " full-resolution vertices lie outside the " << resolutionName(resolution) << " tissue (max "
        << m.skinEmbedding.maxOutsideDistance() << " mm, mean " << m.skinEmbedding.meanOutsideDistance()
        << " mm); they follow the nearest tetrahedron";
      m.warnings.push_back(s.str());
    }
  }
  return m;
}

}  // namespace orthosim
