// Points embedded in tets: reproduced exactly at rest and under any affine map (linear tets are
// exact for affine maps, and points just outside the mesh use the affine extension of their
// nearest tet), nodes follow themselves, points too far out are refused by index and distance,
// coarse and fine meshes agree to their mesh size under a bending, and the real face's surface
// vertices embed onto their own nodes.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "TestData.hpp"
#include "io/TetgenIO.hpp"
#include "mesh/PointEmbedding.hpp"
#include "meshing/BoxMesh.hpp"

namespace orthosim {
namespace {

namespace fs = std::filesystem;

const Eigen::Vector3d kSize(60, 40, 20);

// Uniform random points in [lo, hi].
Eigen::Matrix3Xd randomPoints(int n, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Eigen::Matrix3Xd p(3, n);
  for (int i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a) p(a, i) = lo[a] + u(rng) * (hi[a] - lo[a]);
  return p;
}

// A general affine map: rotation, shear, stretch and translation.
Eigen::Matrix3Xd affine(const Eigen::Matrix3Xd& x) {
  Eigen::Matrix3d A = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  A *= (Eigen::Matrix3d() << 1.1, 0.2, 0.0, 0.0, 0.9, -0.1, 0.05, 0.0, 1.2).finished();
  return (A * x).colwise() + Eigen::Vector3d(5, -3, 2);
}

double maxDistance(const Eigen::Matrix3Xd& a, const Eigen::Matrix3Xd& b) { return (a - b).colwise().norm().maxCoeff(); }

TEST(PointEmbedding, InsidePointsAreExactAtRestAndUnderAnAffineMap) {
  const TetMesh box = makeBoxMesh({kSize, {6, 4, 2}});
  const Eigen::Matrix3Xd p = randomPoints(2000, Eigen::Vector3d::Zero(), kSize, 1);
  const PointEmbedding emb = embedPoints(box, p);
  EXPECT_EQ(emb.numOutside(), 0);
  EXPECT_EQ(emb.maxOutsideDistance(), 0.0);
  EXPECT_EQ(emb.meanOutsideDistance(), 0.0);
  EXPECT_LT(maxDistance(emb.apply(box.rest), p), 1e-11);
  EXPECT_LT(maxDistance(emb.apply(affine(box.rest)), affine(p)), 1e-11);
  for (int i = 0; i < emb.numPoints(); ++i) {
    EXPECT_GE(emb.weights().col(i).minCoeff(), -1e-9) << "point " << i;
    EXPECT_NEAR(emb.weights().col(i).sum(), 1.0, 1e-12);
  }
}

TEST(PointEmbedding, NodesFollowThemselvesUnderAnyDeformation) {
  const TetMesh box = makeBoxMesh({kSize, {6, 4, 2}});
  const PointEmbedding emb = embedPoints(box, box.rest);
  EXPECT_EQ(emb.numOutside(), 0);
  // Random node positions: only a weight of 1 on the node itself reproduces them.
  const Eigen::Matrix3Xd x = randomPoints(box.numNodes(), -kSize, 2 * kSize, 2);
  EXPECT_LT(maxDistance(emb.apply(x), x), 1e-9);
}

TEST(PointEmbedding, PointsJustOutsideFollowAnAffineMapExactly) {
  // Turned, so that tet bounding boxes are no stand-in for the tets.
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(0.5, Eigen::Vector3d(2, -1, 1).normalized()).toRotationMatrix();
  TetMesh box = makeBoxMesh({kSize, {6, 4, 2}});
  box.rest = turn * box.rest;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  // Off each face by 1-2 mm along its normal (that is the distance), then off corners diagonally.
  const int n = 600;
  Eigen::Matrix3Xd p(3, n + 8);
  Eigen::VectorXd expected(n + 8);
  for (int i = 0; i < n; ++i) {
    const int axis = i % 3;
    const bool high = (i / 3) % 2;
    Eigen::Vector3d q = randomPoints(1, Eigen::Vector3d::Zero(), kSize, 100 + i).col(0);
    expected[i] = 1 + u(rng);
    q[axis] = high ? kSize[axis] + expected[i] : -expected[i];
    p.col(i) = q;
  }
  for (int c = 0; c < 8; ++c) {
    const Eigen::Vector3d dir(c & 1 ? 1 : -1, c & 2 ? 1 : -1, c & 4 ? 1 : -1);
    const Eigen::Vector3d corner = kSize.cwiseProduct((dir.array() + 1).matrix() / 2);
    p.col(n + c) = corner + dir;  // sqrt(3) mm out
    expected[n + c] = std::sqrt(3.0);
  }
  p = turn * p;
  const PointEmbedding emb = embedPoints(box, p);
  EXPECT_EQ(emb.numOutside(), n + 8);
  for (int i = 0; i < n + 8; ++i) EXPECT_NEAR(emb.outsideDistance()[i], expected[i], 1e-9) << "point " << i;
  EXPECT_NEAR(emb.maxOutsideDistance(), expected.maxCoeff(), 1e-9);
  EXPECT_NEAR(emb.meanOutsideDistance(), expected.mean(), 1e-9);
  EXPECT_LT(maxDistance(emb.apply(box.rest), p), 1e-11);
  EXPECT_LT(maxDistance(emb.apply(affine(box.rest)), affine(p)), 1e-11);
}

TEST(PointEmbedding, PointBeyondTheLimitIsRefusedByIndexAndDistance) {
  const TetMesh box = makeBoxMesh({kSize, {6, 4, 2}});
  Eigen::Matrix3Xd p = randomPoints(6, Eigen::Vector3d::Zero(), kSize, 4);
  p.col(3) = Eigen::Vector3d(kSize.x() + 12, 20, 10);  // 12 mm beyond the face x = 60
  p.col(5) = Eigen::Vector3d(30, 20, -40);             // 40 mm below
  try {
    embedPoints(box, p);
    FAIL() << "a point 12 mm outside was accepted with the default 10 mm limit";
  } catch (const std::invalid_argument& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("point 3 "), std::string::npos) << msg;
    EXPECT_NE(msg.find("is 12 mm outside"), std::string::npos) << msg;
    EXPECT_NE(msg.find("limit of 10 mm"), std::string::npos) << msg;
    EXPECT_NE(msg.find("2 points in all"), std::string::npos) << msg;
  }
  EmbeddingOptions wide;
  wide.maxOutsideDistance = 50;
  const PointEmbedding emb = embedPoints(box, p, wide);
  EXPECT_EQ(emb.numOutside(), 2);
  EXPECT_NEAR(emb.outsideDistance()[3], 12, 1e-9);
  EXPECT_NEAR(emb.maxOutsideDistance(), 40, 1e-9);
  EXPECT_NEAR(emb.meanOutsideDistance(), 26, 1e-9);

  p(1, 2) = std::nan("");
  EXPECT_THROW(
      try { embedPoints(box, p, wide); } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("point 2 has a non-finite"), std::string::npos) << e.what();
        throw;
      },
      std::invalid_argument);
  EXPECT_THROW(emb.apply(Eigen::Matrix3Xd::Zero(3, box.numNodes() - 1)), std::invalid_argument);
}

TEST(PointEmbedding, CoarseAndFineAgreeToTheirMeshSizeUnderABending) {
  // z += k x^2: linear interpolation errs by exactly k sum_i w_i (x_i - x)^2 (an identity for a
  // quadratic, inside and outside), which is (x - x0)(x0 + hx - x) <= k hx^2 / 4 in a box cell of
  // x-size hx from x0, also above the cell's top (the tet vertices span x0..x0 + hx).
  const double k = 0.005;  // 1/mm: the 60 mm block's end rises 18 mm
  auto bend = [&](const Eigen::Matrix3Xd& x) {
    Eigen::Matrix3Xd y = x;
    y.row(2) += k * x.row(0).cwiseAbs2();
    return y;
  };
  const TetMesh coarse = makeBoxMesh({kSize, {6, 4, 2}});  // hx = 10 mm
  const TetMesh fine = makeBoxMesh({kSize, {24, 16, 8}});  // hx = 2.5 mm
  const Eigen::Matrix3Xd inside = randomPoints(3000, Eigen::Vector3d::Zero(), kSize, 5);
  const Eigen::Matrix3Xd c = embedPoints(coarse, inside).apply(bend(coarse.rest));
  const Eigen::Matrix3Xd f = embedPoints(fine, inside).apply(bend(fine.rest));
  const double coarseErr = maxDistance(c, bend(inside)), fineErr = maxDistance(f, bend(inside));
  std::cout << "bending error: coarse " << coarseErr << " mm, fine " << fineErr << " mm\n";
  EXPECT_LE(coarseErr, k * 10 * 10 / 4 + 1e-9);
  EXPECT_LE(fineErr, k * 2.5 * 2.5 / 4 + 1e-9);
  EXPECT_LT(fineErr, coarseErr / 8);  // second order: 16x smaller for 4x smaller cells
  EXPECT_LE(maxDistance(c, f), k * (10 * 10 + 2.5 * 2.5) / 4 + 1e-9);

  // The top skin 1.5 mm above the block: each mesh's extension of its nearest tet.
  Eigen::Matrix3Xd above = randomPoints(1000, Eigen::Vector3d::Zero(), kSize, 6);
  above.row(2).setConstant(kSize.z() + 1.5);
  const Eigen::Matrix3Xd ca = embedPoints(coarse, above).apply(bend(coarse.rest));
  const Eigen::Matrix3Xd fa = embedPoints(fine, above).apply(bend(fine.rest));
  EXPECT_LE(maxDistance(ca, bend(above)), k * 10 * 10 / 4 + 1e-9);
  EXPECT_LE(maxDistance(fa, bend(above)), k * 2.5 * 2.5 / 4 + 1e-9);
  EXPECT_LE(maxDistance(ca, fa), k * (10 * 10 + 2.5 * 2.5) / 4 + 1e-9);
}

TEST(PointEmbedding, TwentyThousandPointsInTwentyThousandTets) {
  const TetMesh box = makeBoxMesh({kSize, cellsForTetCount(kSize, 20000)});
  ASSERT_GT(box.numTets(), 15000);
  const Eigen::Matrix3Xd p = randomPoints(20000, Eigen::Vector3d::Zero(), kSize, 7);
  const PointEmbedding emb = embedPoints(box, p);
  EXPECT_EQ(emb.numPoints(), 20000);
  EXPECT_EQ(emb.numOutside(), 0);
  EXPECT_LT(maxDistance(emb.apply(box.rest), p), 1e-11);
}

TEST(PointEmbedding, RealFaceSurfaceVerticesEmbedOntoTheirNodes) {
  const fs::path dir = fs::path(ORTHOSIM_CASES_DIR) / "artisynth_face";
  SKIP_WITHOUT_SHARED_DATA(dir / "face_volume.node", dir / "face_volume.ele", dir / "face_surface.obj",
                           dir / "face_surface_vertex_to_node.txt");
  const TetMesh face = readTetgen((dir / "face_volume.node").string(), (dir / "face_volume.ele").string()).mesh;
  std::vector<Eigen::Vector3d> v;
  std::ifstream obj(dir / "face_surface.obj");
  for (std::string line; std::getline(obj, line);)
    if (line.rfind("v ", 0) == 0) {
      std::istringstream in(line.substr(2));
      Eigen::Vector3d x;
      in >> x.x() >> x.y() >> x.z();
      v.push_back(x);
    }
  std::vector<int> node;
  std::ifstream map(dir / "face_surface_vertex_to_node.txt");
  for (int i; map >> i;) node.push_back(i);
  ASSERT_EQ(v.size(), node.size());
  Eigen::Matrix3Xd p(3, v.size());
  for (size_t i = 0; i < v.size(); ++i) p.col(i) = v[i];

  const PointEmbedding emb = embedPoints(face, p);
  EXPECT_EQ(emb.numOutside(), 0);
  EXPECT_LT(maxDistance(emb.apply(face.rest), p), 1e-9);
  // Under random node positions each vertex still lands on its own node.
  const Eigen::Matrix3Xd x =
      face.rest + randomPoints(face.numNodes(), -Eigen::Vector3d::Ones(), Eigen::Vector3d::Ones(), 8);
  const Eigen::Matrix3Xd y = emb.apply(x);
  double worst = 0;
  for (size_t i = 0; i < node.size(); ++i) worst = std::max(worst, (y.col(i) - x.col(node[i])).norm());
  EXPECT_LT(worst, 1e-6);
}

}  // namespace
}  // namespace orthosim
