// buildTissueMesh(): tets fill exactly the tissue (envelope minus solids, inner cavities left
// empty), the labelled boundary is the mesh boundary with vertex i == node i, interface node lists
// lie exactly on their solids, the skin carries uv, and a small timing figure for the record.
#include <gtest/gtest.h>

#include <chrono>
#include <iostream>
#include <set>

#include "TissueScene.hpp"
#include "mesh/BoundaryFaces.hpp"
#include "mesh/SurfaceDistance.hpp"
#include "meshing/TissueMesh.hpp"

namespace orthosim {
namespace {

double tetVolume(const TetMesh& m) {
  double v = 0;
  for (int e = 0; e < m.numTets(); ++e) v += m.signedVolume(e, m.rest);
  return v;
}

Eigen::Matrix3Xd nodes(const TetMesh& m, const std::vector<int>& ids) {
  Eigen::Matrix3Xd x(3, ids.size());
  for (size_t i = 0; i < ids.size(); ++i) x.col(i) = m.rest.col(ids[i]);
  return x;
}

TEST(TissueMesh, TetsFillExactlyTheTissueWithLabelledInterfaces) {
  const test::TissueScene scene = test::tissueScene(4, 3);
  TissueMeshOptions o;
  o.skinTriangles = 1200;
  o.solidNames = scene.names;
  o.refine = {RefineRegion{Eigen::Vector3d(0, -50, 0), 20, 3.0}};
  const TissueMeshResult r = buildTissueMesh(scene.skin, scene.solids, o);

  // Volume: the tets fill the boundary and nothing else (the inner bone is a hole).
  EXPECT_EQ(r.cavities, 1);
  EXPECT_NEAR(tetVolume(r.mesh), r.boundary.signedVolume(), 1e-6 * r.boundary.signedVolume());
  EXPECT_LT(r.boundary.signedVolume(), scene.skin.signedVolume() - scene.solids[0].signedVolume());
  EXPECT_GT(r.quality.minVolume, 0);

  // Boundary vertex i is node i, and the mesh boundary is exactly the labelled boundary.
  ASSERT_LE(r.boundary.numVertices(), r.mesh.numNodes());
  EXPECT_TRUE(r.mesh.rest.leftCols(r.boundary.numVertices()) == r.boundary.vertices);
  const Eigen::Matrix3Xi faces = boundaryFaces(r.mesh);
  ASSERT_EQ(faces.cols(), r.boundary.numTriangles());
  std::set<std::array<int, 3>> a, b;
  auto key = [](Eigen::Vector3i f) {
    std::array<int, 3> k{f[0], f[1], f[2]};
    std::rotate(k.begin(), std::min_element(k.begin(), k.end()), k.end());
    return k;
  };
  for (int t = 0; t < faces.cols(); ++t) a.insert(key(faces.col(t))), b.insert(key(r.boundary.triangles.col(t)));
  EXPECT_EQ(a, b);

  // Interface nodes lie on their solid, skin nodes on the envelope (exactly: never moved).
  ASSERT_EQ(r.solidNodes.size(), 3u);
  for (int k = 0; k < 3; ++k) {
    ASSERT_FALSE(r.solidNodes[k].empty()) << k;
    EXPECT_TRUE(std::is_sorted(r.solidNodes[k].begin(), r.solidNodes[k].end()));
    const Eigen::VectorXd d =
        distancesToSurface(scene.solids[k].vertices, scene.solids[k].triangles, nodes(r.mesh, r.solidNodes[k]));
    EXPECT_LT(d.maxCoeff(), 1e-9 * 100) << "solid " << k;
  }
  EXPECT_LT(distancesToSurface(scene.skin.vertices, scene.skin.triangles, nodes(r.mesh, r.skinNodes)).maxCoeff(),
            1e-9 * 100);
  // Seams: nodes in both the skin and a solid list (bone and cavity cross the skin).
  std::vector<int> seam;
  std::set_intersection(r.skinNodes.begin(), r.skinNodes.end(), r.solidNodes[1].begin(), r.solidNodes[1].end(),
                        std::back_inserter(seam));
  EXPECT_GT(seam.size(), 10u);

  // Skin: label-0 triangles, uv of the affine field at every vertex, vertices are their nodes.
  EXPECT_EQ(r.skin.numTriangles(), static_cast<int>(std::count(r.boundaryLabel.begin(), r.boundaryLabel.end(), 0)));
  EXPECT_NEAR(r.skin.numTriangles(), o.skinTriangles, 0.1 * o.skinTriangles);
  ASSERT_TRUE(r.skin.hasUv());
  for (int i = 0; i < r.skin.numVertices(); ++i) {
    EXPECT_TRUE(r.skin.vertices.col(i) == r.mesh.rest.col(r.skinVertexNode[i]));
    EXPECT_LT((r.skin.uv.col(i) - test::affineUv(r.skin.vertices.col(i))).norm(), 1e-12);
  }
  EXPECT_GT(r.tetgen_s, 0);
}

TEST(TissueMesh, BadInputIsNamed) {
  const test::TissueScene scene = test::tissueScene(3, 2);
  SurfaceMesh open = scene.solids[2];
  open.triangles.conservativeResize(3, open.numTriangles() - 1);
  TissueMeshOptions o;
  o.solidNames = {"skull", "mandible", "oral cavity"};
  try {
    buildTissueMesh(scene.skin, {scene.solids[0], scene.solids[1], open}, o);
    ADD_FAILURE() << "accepted an open cavity";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("solid 2 (oral cavity): not closed"), std::string::npos) << e.what();
  }
}

// The stages' times for the record (label perf, outside the default run: about a minute): an
// 82k-triangle skin with 20k-triangle bones meshed at 3000 and 20000 skin triangles.
TEST(TissueMeshPerf, StageTimesAtCoarseAndFineTargets) {
  const test::TissueScene scene = test::tissueScene(6, 5);
  for (int target : {3000, 20000}) {
    TissueMeshOptions o;
    o.skinTriangles = target;
    const auto start = std::chrono::steady_clock::now();
    const TissueMeshResult r = buildTissueMesh(scene.skin, scene.solids, o);
    const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cout << "skin " << scene.skin.numTriangles() << " + solids " << scene.solids[0].numTriangles()
              << " x3, target " << target << ": total " << total << " s (boolean " << r.boolean_s << ", simplify "
              << r.simplify_s << ", tetgen " << r.tetgen_s << "); boundary " << r.booleanTriangles << " -> "
              << r.boundary.numTriangles() << " (skin " << r.simplify.skinTriangles << ", rounds " << r.simplify.rounds
              << ", frozen " << r.simplify.frozenTriangles << "), " << r.quality << "\n";
    EXPECT_NEAR(r.simplify.skinTriangles, target, 0.1 * target);
  }
}

}  // namespace
}  // namespace orthosim
