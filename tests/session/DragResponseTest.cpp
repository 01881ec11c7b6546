// The drag view's error figures: how far the linear face was from the converged one,
// on the full-resolution skin, overall and at the lips.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "phantom/PhantomCase.hpp"
#include "scene/CaseModel.hpp"
#include "session/DragResponse.hpp"
#include "solver/Model.hpp"

namespace orthosim::server {
namespace {

TEST(DragResponse, LinearErrorIsMeasuredOnTheSkinAndAtTheLips) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("orthosim_drag_test_" + std::to_string(::getpid()));
  const CaseSpec spec = loadCaseFile(writePhantomCase(0, (dir / "case").string()));
  const CaseModel coarse = buildCaseModel(spec, Resolution::Coarse, {ORTHOSIM_TEST_CACHE_DIR});
  fs::remove_all(dir);

  const std::vector<int> lips = lipVertices(coarse);
  ASSERT_FALSE(lips.empty());
  for (int i : lips) {
    double nearest = 1e9;
    for (const char* name : {"labrale_superius", "labrale_inferius", "stomion"})
      nearest = std::min(nearest, (coarse.tissue.skin.vertices.col(i) - coarse.spec.landmarks.at(name)).norm());
    EXPECT_LT(nearest, 10.0) << "skin vertex " << i << " is no lip vertex";
  }
  EXPECT_LT(lips.size(), static_cast<size_t>(coarse.tissue.skin.numVertices()) / 4);

  // Shifts of the whole tissue move every skin vertex by the same vector (the embedding is affine).
  SimState from;
  from.x = coarse.scene.mesh.rest;
  SimState converged = from, linear = from;
  converged.x.colwise() += Eigen::Vector3d(0, 0, 2);
  linear.x.colwise() += Eigen::Vector3d(0, 0.3, 2.4);  // 0.5 mm off everywhere
  const nlohmann::json e = linearErrorJson(coarse, linear, converged, from, lips);
  EXPECT_NEAR(e["max_mm"].get<double>(), 0.5, 1e-9);
  EXPECT_NEAR(e["lips_mm"].get<double>(), 0.5, 1e-9);
  EXPECT_NEAR(e["moved_mm"].get<double>(), 2.0, 1e-9);

  // Off at one lip vertex's nodes only: that vertex is 1 mm off, and the lips carry the error.
  const int lip = lips.front();
  SimState bent = converged;
  for (int a = 0; a < 4; ++a) bent.x.col(coarse.skinEmbedding.nodes()(a, lip)) += Eigen::Vector3d(1, 0, 0);
  const nlohmann::json b = linearErrorJson(coarse, bent, converged, from, lips);
  EXPECT_GE(b["lips_mm"].get<double>(), 1.0 - 1e-9) << "a vertex whose four nodes all moved 1 mm moved 1 mm";
  EXPECT_GE(b["max_mm"].get<double>(), b["lips_mm"].get<double>());
  SimState away = converged;  // far from the mouth: the lips are not off at all
  int far = -1;
  for (int i = 0; i < coarse.skinEmbedding.numPoints() && far < 0; ++i)
    if ((coarse.tissue.skin.vertices.col(i) - coarse.spec.landmarks.at("stomion")).norm() > 60) far = i;
  ASSERT_GE(far, 0);
  for (int a = 0; a < 4; ++a) away.x.col(coarse.skinEmbedding.nodes()(a, far)) += Eigen::Vector3d(1, 0, 0);
  const nlohmann::json c = linearErrorJson(coarse, away, converged, from, lips);
  EXPECT_EQ(c["lips_mm"].get<double>(), 0.0);
  EXPECT_GE(c["max_mm"].get<double>(), 1.0 - 1e-9);
}

}  // namespace
}  // namespace orthosim::server
