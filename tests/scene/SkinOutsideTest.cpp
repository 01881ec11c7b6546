// A display skin that lies partly outside the tissue it is embedded in (what a simplified coarse
// skin does to a patient's nose and ears): the report names each patch, how far its farthest
// point lies outside, where, and the nearest landmark; and the skin carried by the deformed
// tissue stays continuous where the points outside change their nearest tetrahedron.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "mesh/BoundaryFaces.hpp"
#include "mesh/PointEmbedding.hpp"
#include "meshing/BoxMesh.hpp"
#include "scene/SkinOutside.hpp"

namespace orthosim {
namespace {

const Eigen::Vector3d kSize(60, 40, 20);

// The boundary of a 1 mm box mesh as a skin, with a 4 mm bump on the top face round (15, 20) and
// a 2 mm bump on the face x = 60 round (y, z) = (20, 10): those lie outside the 10 mm tissue.
SurfaceMesh bumpySkin() {
  const TetMesh fine = makeBoxMesh({kSize, Eigen::Vector3i(60, 40, 20)});
  const Eigen::Matrix3Xi faces = boundaryFaces(fine);
  std::vector<int> index(fine.numNodes(), -1);
  SurfaceMesh skin;
  std::vector<Eigen::Vector3d> v;
  skin.triangles.resize(3, faces.cols());
  for (Eigen::Index t = 0; t < faces.cols(); ++t)
    for (int k = 0; k < 3; ++k) {
      int& i = index[faces(k, t)];
      if (i < 0) i = static_cast<int>(v.size()), v.push_back(fine.rest.col(faces(k, t)));
      skin.triangles(k, t) = i;
    }
  skin.vertices.resize(3, static_cast<Eigen::Index>(v.size()));
  for (size_t i = 0; i < v.size(); ++i) {
    Eigen::Vector3d p = v[i];
    const double top = (Eigen::Vector2d(p.x(), p.y()) - Eigen::Vector2d(15, 20)).squaredNorm() / 64.0;
    if (p.z() == kSize.z() && top < 1) p.z() += 4 * (1 - top);
    const double side = (Eigen::Vector2d(p.y(), p.z()) - Eigen::Vector2d(20, 10)).squaredNorm() / 36.0;
    if (p.x() == kSize.x() && side < 1) p.x() += 2 * (1 - side);
    skin.vertices.col(static_cast<Eigen::Index>(i)) = p;
  }
  return skin;
}

// Each vertical fibre at x turned by k x about its foot, and a shear in y: a smooth deformation
// whose gradient varies from tet to tet.
Eigen::Matrix3Xd bend(const Eigen::Matrix3Xd& x) {
  const double k = 0.01;  // rad/mm: the 60 mm block's end turns by 0.6 rad
  Eigen::Matrix3Xd y(3, x.cols());
  for (Eigen::Index i = 0; i < x.cols(); ++i) {
    const Eigen::Vector3d p = x.col(i);
    y.col(i) = Eigen::Vector3d(p.x() - p.z() * std::sin(k * p.x()), p.y() + 0.002 * p.x() * p.z(),
                               p.z() * std::cos(k * p.x()));
  }
  return y;
}

TEST(SkinOutside, EachPatchOutsideIsReportedWithItsFarthestPointDistanceAndLandmark) {
  const TetMesh tissue = makeBoxMesh({kSize, Eigen::Vector3i(6, 4, 2)});
  const SurfaceMesh skin = bumpySkin();
  const PointEmbedding embedding = embedPoints(tissue, skin.vertices);
  const std::map<std::string, Eigen::Vector3d> landmarks = {
      {"pronasale", {15, 20, 25}}, {"tragion_right", {62, 20, 12}}, {"menton", {30, 20, -5}}};
  const SkinOutside s = findSkinOutside(skin, embedding, landmarks);

  int bumped = 0;  // every vertex the bumps moved lies outside, and only those
  for (int i = 0; i < skin.numVertices(); ++i) {
    const Eigen::Vector3d p = skin.vertices.col(i);
    bumped += p.z() > kSize.z() || p.x() > kSize.x();
  }
  EXPECT_EQ(s.vertices, skin.numVertices());
  EXPECT_EQ(s.outside, bumped);
  EXPECT_NEAR(s.maxDistance, 4.0, 1e-9);
  ASSERT_EQ(s.patches.size(), 2u);
  EXPECT_NEAR(s.patches[0].maxDistance, 4.0, 1e-9);
  EXPECT_LT((s.patches[0].farthest - Eigen::Vector3d(15, 20, 24)).norm(), 1e-9);
  EXPECT_EQ(s.patches[0].landmark, "pronasale");
  EXPECT_NEAR(s.patches[0].landmarkDistance, 1.0, 1e-9);
  EXPECT_NEAR(s.patches[1].maxDistance, 2.0, 1e-9);
  EXPECT_LT((s.patches[1].farthest - Eigen::Vector3d(62, 20, 10)).norm(), 1e-9);
  EXPECT_EQ(s.patches[1].landmark, "tragion_right");
  EXPECT_EQ(s.patches[0].vertices + s.patches[1].vertices, s.beyond);

  const std::string text = describeSkinOutside(s, "coarse", 3000);
  std::cout << text << "\n";
  char share[64];
  std::snprintf(share, sizeof share, "%.0f%% of the display skin (%d of %d vertices)", 100.0 * bumped / s.vertices,
                bumped, s.vertices);
  EXPECT_NE(text.find(share), std::string::npos) << text;
  EXPECT_NE(text.find("outside the coarse tissue"), std::string::npos) << text;
  EXPECT_NE(text.find("simplified to 3000 triangles"), std::string::npos) << text;
  EXPECT_NE(text.find("4.0 mm at (15.0, 20.0, 24.0) mm, 1.0 mm from pronasale"), std::string::npos) << text;
  EXPECT_NE(text.find("2.0 mm at (62.0, 20.0, 10.0) mm, 2.0 mm from tragion_right"), std::string::npos) << text;
  EXPECT_LT(text.find("pronasale"), text.find("tragion_right")) << "farthest first: " << text;
}

TEST(SkinOutside, TheSkinCarriedByADeformedTissueStaysContinuousOutsideIt) {
  const TetMesh tissue = makeBoxMesh({kSize, Eigen::Vector3i(6, 4, 2)});
  const SurfaceMesh skin = bumpySkin();
  const PointEmbedding embedding = embedPoints(tissue, skin.vertices);
  // At rest and under an affine map the skin is reproduced exactly, outside points included.
  Eigen::Matrix3d a;
  a << 1.1, 0.2, 0, -0.1, 0.9, 0.3, 0.05, 0, 1.2;
  const Eigen::Vector3d b(3, -2, 7);
  EXPECT_LT((embedding.apply(tissue.rest) - skin.vertices).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT(
      (embedding.apply((a * tissue.rest).colwise() + b) - ((a * skin.vertices).colwise() + b)).cwiseAbs().maxCoeff(),
      1e-9);

  // Bent: how far each skin edge departs from the bent skin's, per mm of edge. Points outside
  // that change their nearest tetrahedron must not part, beyond what the tissue's own linear
  // interpolation does to the edges inside it.
  const Eigen::Matrix3Xd y = embedding.apply(bend(tissue.rest)), exact = bend(skin.vertices);
  // The extension of each point's own nearest tetrahedron (what the embedding did before), for
  // comparison: it parts neighbours whose nearest tetrahedra differ.
  const Eigen::Matrix3Xd bent = bend(tissue.rest);
  Eigen::Matrix3Xd own = y;
  for (int i = 0; i < embedding.numPoints(); ++i) {
    if (embedding.outsideDistance()[i] == 0) continue;
    const int e = embedding.tets()[i];
    Eigen::Matrix3d d, db;
    for (int k = 0; k < 3; ++k) {
      d.col(k) = tissue.rest.col(tissue.tets(k + 1, e)) - tissue.rest.col(tissue.tets(0, e));
      db.col(k) = bent.col(tissue.tets(k + 1, e)) - bent.col(tissue.tets(0, e));
    }
    own.col(i) =
        bent.col(tissue.tets(0, e)) + db * d.inverse() * (skin.vertices.col(i) - tissue.rest.col(tissue.tets(0, e)));
  }
  double inside = 0, outside = 0, ownOutside = 0;
  for (int t = 0; t < skin.numTriangles(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int i = skin.triangles(k, t), j = skin.triangles((k + 1) % 3, t);
      const double length = (skin.vertices.col(i) - skin.vertices.col(j)).norm();
      const auto departure = [&](const Eigen::Matrix3Xd& z) {
        return ((z.col(i) - z.col(j)) - (exact.col(i) - exact.col(j))).norm() / length;
      };
      if (embedding.outsideDistance()[i] == 0 && embedding.outsideDistance()[j] == 0) {
        inside = std::max(inside, departure(y));
      } else {
        outside = std::max(outside, departure(y));
        ownOutside = std::max(ownOutside, departure(own));
      }
    }
  std::cout << "edge departure per mm: inside " << inside << ", outside " << outside
            << ", outside with each point's own tet " << ownOutside << "\n";
  EXPECT_LT(outside, 1.5 * inside);
  EXPECT_GT(ownOutside, 1.5 * inside) << "the bending does not tell a continuous embedding from a torn one";
}

}  // namespace
}  // namespace orthosim
