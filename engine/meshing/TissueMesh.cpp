#include "meshing/TissueMesh.hpp"

#include <algorithm>
#include <chrono>
#include <map>
#include <stdexcept>
#include <tuple>

#include "meshing/CavityPoints.hpp"
#include "meshing/TissueBoolean.hpp"

namespace orthosim {
namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::vector<int> sortedUnique(std::vector<int> v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v;
}

}  // namespace

TissueMeshResult buildTissueMesh(const SurfaceMesh& envelope, const std::vector<SurfaceMesh>& solids,
                                 const TissueMeshOptions& options) {
  TissueMeshResult r;
  auto start = std::chrono::steady_clock::now();
  const LabelledSurface full = subtractSurfaces(envelope, solids, options.solidNames);
  r.boolean_s = secondsSince(start);
  r.booleanTriangles = full.surface.numTriangles();

  start = std::chrono::steady_clock::now();
  SimplifyOptions simplify;
  simplify.skinTriangles = options.skinTriangles;
  simplify.refine = options.refine;
  simplify.interfaceDensity = options.interfaceDensity;
  const LabelledSurface coarse = simplifySurface(full, simplify, &r.simplify);
  r.simplify_s = secondsSince(start);
  r.warnings = coarse.warnings;

  start = std::chrono::steady_clock::now();
  TetgenOptions tetgen = options.tetgen;
  if (!tetgen.preserveSurface)
    throw std::invalid_argument("buildTissueMesh: tetgen.preserveSurface must stay on (interfaces are boundary faces)");
  const Eigen::Matrix3Xd holes = cavityPoints(coarse.surface.vertices, coarse.surface.triangles);
  r.cavities = static_cast<int>(holes.cols());
  Eigen::Matrix3Xd allHoles(3, tetgen.holes.cols() + holes.cols());
  allHoles << tetgen.holes, holes;
  tetgen.holes = allHoles;
  r.mesh = tetrahedralize(coarse.surface.vertices, coarse.surface.triangles, tetgen, &r.quality);
  r.tetgen_s = secondsSince(start);

  r.boundary = coarse.surface;
  r.boundaryLabel = coarse.label;
  r.solidNodes.assign(solids.size(), {});
  const Eigen::Matrix3Xi& F = r.boundary.triangles;
  for (int t = 0; t < F.cols(); ++t) {
    std::vector<int>& nodes = coarse.label[t] == 0 ? r.skinNodes : r.solidNodes[coarse.label[t] - 1];
    for (int c = 0; c < 3; ++c) nodes.push_back(F(c, t));
  }
  r.skinNodes = sortedUnique(std::move(r.skinNodes));
  for (auto& nodes : r.solidNodes) nodes = sortedUnique(std::move(nodes));

  // Skin: one vertex per (node, uv) pair.
  std::map<std::tuple<int, double, double>, int> vertexOf;
  std::vector<Eigen::Vector3i> skinTriangles;
  std::vector<Eigen::Vector2d> skinUv;
  for (int t = 0; t < F.cols(); ++t) {
    if (coarse.label[t] != 0) continue;
    Eigen::Vector3i f;
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector2d uv =
          coarse.hasUv() ? Eigen::Vector2d(coarse.cornerUv.col(3 * t + c)) : Eigen::Vector2d::Zero();
      const auto [it, inserted] =
          vertexOf.emplace(std::make_tuple(F(c, t), uv.x(), uv.y()), static_cast<int>(r.skinVertexNode.size()));
      if (inserted) r.skinVertexNode.push_back(F(c, t)), skinUv.push_back(uv);
      f[c] = it->second;
    }
    skinTriangles.push_back(f);
  }
  r.skin.vertices.resize(3, r.skinVertexNode.size());
  for (size_t i = 0; i < r.skinVertexNode.size(); ++i) r.skin.vertices.col(i) = r.mesh.rest.col(r.skinVertexNode[i]);
  if (coarse.hasUv()) {
    r.skin.uv.resize(2, skinUv.size());
    for (size_t i = 0; i < skinUv.size(); ++i) r.skin.uv.col(i) = skinUv[i];
  }
  r.skin.triangles.resize(3, skinTriangles.size());
  for (size_t t = 0; t < skinTriangles.size(); ++t) r.skin.triangles.col(t) = skinTriangles[t];
  return r;
}

}  // namespace orthosim
