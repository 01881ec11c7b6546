#include "render/CaseBones.hpp"

#include "io/SurfaceImport.hpp"
#include "scene/BoneFragments.hpp"

namespace orthosim::render {
namespace {

Eigen::Matrix3Xd centroids(const SurfaceMesh& m) {
  Eigen::Matrix3Xd c(3, m.numTriangles());
  for (int t = 0; t < m.numTriangles(); ++t)
    c.col(t) =
        (m.vertices.col(m.triangles(0, t)) + m.vertices.col(m.triangles(1, t)) + m.vertices.col(m.triangles(2, t))) /
        3.0;
  return c;
}

// The triangles of `bone` in fragment f, renumbered over the vertices they use.
SurfaceMesh piece(const SurfaceMesh& bone, const std::vector<int>& fragmentOf, int f) {
  std::vector<int> newIndex(static_cast<size_t>(bone.numVertices()), -1);
  std::vector<int> vertices, triangles;
  for (int t = 0; t < bone.numTriangles(); ++t) {
    if (fragmentOf[static_cast<size_t>(t)] != f) continue;
    for (int k = 0; k < 3; ++k) {
      int& id = newIndex[static_cast<size_t>(bone.triangles(k, t))];
      if (id < 0) {
        id = static_cast<int>(vertices.size());
        vertices.push_back(bone.triangles(k, t));
      }
      triangles.push_back(id);
    }
  }
  SurfaceMesh out;
  out.vertices.resize(3, static_cast<Eigen::Index>(vertices.size()));
  for (size_t i = 0; i < vertices.size(); ++i)
    out.vertices.col(static_cast<Eigen::Index>(i)) = bone.vertices.col(vertices[i]);
  out.triangles =
      Eigen::Map<const Eigen::Matrix3Xi>(triangles.data(), 3, static_cast<Eigen::Index>(triangles.size() / 3));
  return out;
}

}  // namespace

std::vector<BonePiece> caseBonePieces(const CaseModel& model) {
  const CaseSpec& spec = model.spec;
  std::vector<BoneGroup> groups;
  for (size_t b = 0; b < spec.bones.size(); ++b) groups.push_back({spec.bones[b].name, model.tissue.boneNodes[b]});
  std::vector<BonePiece> pieces;
  for (const CaseBone& bone : spec.bones) {
    SurfaceMesh surface;
    try {
      surface = importSurface(bone.surface);
    } catch (const std::exception& e) {
      throw SceneError(spec.file + ": bone '" + bone.name + "': " + e.what());
    }
    const std::vector<int> fragmentOf = locateOnBone(groups, spec.regions, bone.name, centroids(surface));
    for (size_t f = 0; f < model.coupling.fragments.size(); ++f) {
      if (model.coupling.fragmentBone[f] != bone.name) continue;
      BonePiece p{model.coupling.fragments[f], static_cast<int>(f), false,
                  piece(surface, fragmentOf, static_cast<int>(f))};
      p.fixed = bone.fixed && p.fragment == bone.name;  // a fragment cut from a fixed bone moves
      if (p.surface.numTriangles() > 0) pieces.push_back(std::move(p));
    }
  }
  return pieces;
}

}  // namespace orthosim::render
