#include "scene/CaseModel.hpp"

#include <set>
#include <sstream>

#include "io/SurfaceImport.hpp"
#include "mesh/BoundaryFaces.hpp"
#include "mesh/SurfaceCheck.hpp"
#include "mesh/SurfaceDistance.hpp"
#include "meshing/CutCaps.hpp"
#include "scene/SceneFields.hpp"
#include "scene/SkinOutside.hpp"

namespace orthosim {

namespace {

// The bone's triangles that lie in fragment f (by their centroids), as a surface of their own.
SurfaceMesh trianglesOf(const SurfaceMesh& bone, const std::vector<int>& fragmentOf, int f) {
  SurfaceMesh out;
  out.vertices = bone.vertices;
  std::vector<int> keep;
  for (int t = 0; t < bone.numTriangles(); ++t)
    if (fragmentOf[t] == f) keep.push_back(t);
  out.triangles.resize(3, static_cast<Eigen::Index>(keep.size()));
  for (size_t k = 0; k < keep.size(); ++k)
    out.triangles.col(static_cast<Eigen::Index>(k)) = bone.triangles.col(keep[k]);
  return out;
}

// Contact pairs of the case: for every listed bone and every fragment cut from it, the fragment's
// part of the bone surface, capped where the cuts opened it, against the tissue's free
// inner-surface nodes within range of it.
std::vector<ContactSpec> caseContacts(const CaseSpec& spec, const CaseTissue& tissue, const Scene& scene,
                                      const std::vector<BoneGroup>& groups) {
  std::vector<ContactSpec> out;
  if (spec.contacts.empty()) return out;
  // Nodes that may touch: on the boundary, off the skin, not held by bone or a fixed set.
  std::vector<char> held(scene.mesh.numNodes(), 0), skin(scene.mesh.numNodes(), 0), boundary(scene.mesh.numNodes(), 0);
  for (int n : tissue.skinNodes) skin[n] = 1;
  for (const FragmentSpec& f : scene.fragments)
    for (int n : f.nodes) held[n] = 1;
  for (const BlendedNode& b : scene.blended) held[b.node] = 1;
  for (const FixedSpec& f : scene.fixed)
    if (f.components[0] && f.components[1] && f.components[2])
      for (int n : f.nodes) held[n] = 1;
  const Eigen::Matrix3Xi faces = boundaryFaces(scene.mesh);
  for (Eigen::Index i = 0; i < faces.size(); ++i) boundary[faces.data()[i]] = 1;
  std::vector<int> candidates;
  for (int n = 0; n < scene.mesh.numNodes(); ++n)
    if (boundary[n] && !held[n] && !skin[n]) candidates.push_back(n);
  Eigen::Matrix3Xd points(3, static_cast<Eigen::Index>(candidates.size()));
  for (size_t k = 0; k < candidates.size(); ++k)
    points.col(static_cast<Eigen::Index>(k)) = scene.mesh.rest.col(candidates[k]);
  if (candidates.empty()) return out;
  // How deep below the skin each candidate lies, for contacts limited to the lips and cheeks.
  Eigen::VectorXd depth;
  for (const CaseContact& c : spec.contacts)
    if (c.maxDepthMm > 0 && depth.size() == 0) {
      if (tissue.skin.numTriangles() == 0)
        throw SceneError(spec.file + ": contact: max_depth_mm needs the case's skin surface, and it has none");
      depth = distancesToSurface(tissue.skin.vertices, tissue.skin.triangles, points);
    }

  for (size_t c = 0; c < spec.contacts.size(); ++c)
    for (const std::string& boneName : spec.contacts[c].bones) {
      size_t b = 0;
      while (spec.bones[b].name != boneName) ++b;
      SurfaceMesh bone = importSurface(spec.bones[b].surface);
      checkSurface(bone, spec.file + ": bones[" + std::to_string(b) + "].surface",
                   SurfaceRequirement::OpenAllowed);  // outward
      Eigen::Matrix3Xd centroids(3, bone.numTriangles());
      for (int t = 0; t < bone.numTriangles(); ++t)
        centroids.col(t) = (bone.vertices.col(bone.triangles(0, t)) + bone.vertices.col(bone.triangles(1, t)) +
                            bone.vertices.col(bone.triangles(2, t))) /
                           3.0;
      const std::vector<int> fragmentOf = locateOnBone(groups, spec.regions, boneName, centroids);
      std::set<int> fragments(fragmentOf.begin(), fragmentOf.end());
      for (int f : fragments) {
        ContactSpec contact;
        contact.fragment = scene.fragments[f].name;
        contact.name = boneName + " (" + contact.fragment + ")";
        contact.surface = capCutOpenings(trianglesOf(bone, fragmentOf, f), bone).surface;
        contact.stiffness = spec.contacts[c].stiffness;
        const Eigen::VectorXd d = distancesToSurface(contact.surface.vertices, contact.surface.triangles, points);
        for (size_t k = 0; k < candidates.size(); ++k)
          if (d[static_cast<Eigen::Index>(k)] <= spec.contacts[c].rangeMm &&
              (spec.contacts[c].maxDepthMm <= 0 || depth[static_cast<Eigen::Index>(k)] <= spec.contacts[c].maxDepthMm))
            contact.nodes.push_back(candidates[k]);
        if (!contact.nodes.empty()) out.push_back(std::move(contact));
      }
    }
  return out;
}

}  // namespace

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
  scene.landmarks = spec.landmarks;

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
  try {
    scene.contacts = caseContacts(spec, tissue, scene, groups);
  } catch (const std::exception& e) {
    throw SceneError(spec.file + ": contact: " + e.what());
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
    // only distances that show on screen are worth a warning, and it says where and why.
    const SkinOutside outside = findSkinOutside(m.tissue.skin, m.skinEmbedding, spec.landmarks);
    if (outside.maxDistance > outside.threshold)
      m.warnings.push_back(describeSkinOutside(outside, resolutionName(resolution), m.tissue.skinTriangles));
  }
  return m;
}

}  // namespace orthosim
