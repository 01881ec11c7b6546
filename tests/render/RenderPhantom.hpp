#pragma once
// The phantom (class I) for renderer tests: written as a case once per test process, its coarse
// model built through a tissue cache in the build folder that all test processes share (ctest runs
// each test in a process of its own, and meshing takes seconds), and the skin's texture read.
// Helpers look at rendered images: which pixels the skin covers, what colour a pixel has.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <memory>

#include "phantom/PhantomCase.hpp"
#include "render/CaseView.hpp"
#include "render/ClinicalView.hpp"
#include "render/Renderer.hpp"
#include "scene/CaseModel.hpp"
#include "solver/PlanSolver.hpp"

namespace orthosim::render::test {

class RenderPhantom : public ::testing::Test {
 protected:
  static constexpr int kWidth = 320, kHeight = 240;

  static void SetUpTestSuite() {
    namespace fs = std::filesystem;
    dir_ = new fs::path(fs::temp_directory_path() / ("orthosim_render_test_" + std::to_string(::getpid())));
    const CaseSpec spec = loadCaseFile(writePhantomCase(0, (*dir_ / "case").string()));
    model_ = new CaseModel(buildCaseModel(spec, Resolution::Coarse, {ORTHOSIM_TEST_CACHE_DIR}));
    texture_ = new RgbImage(caseTexture(spec));
  }
  static void TearDownTestSuite() {
    delete texture_;
    delete model_;
    std::filesystem::remove_all(*dir_);
    delete dir_;
  }

  static const CaseModel& model() { return *model_; }
  static const RgbImage& texture() { return *texture_; }
  static std::filesystem::path dir() { return *dir_; }
  static Eigen::Vector3d softLandmark(const std::string& name) { return model().spec.landmarks.at(name); }

  // The plan solved on the coarse model: `plan` replaces the case's (5 mm Le Fort I advancement).
  static SimState solve(const std::map<std::string, FragmentMotion>& plan) {
    Scene scene = model().scene;
    scene.plan = plan;
    Model m(std::move(scene));
    const SolveResult r = solveScene(m);
    EXPECT_TRUE(r.converged) << r.error;
    return r.state;
  }
  static SimState solveCasePlan() { return solve(model().spec.plan); }

  // A renderer without multisampling: edges are not blended, so colours can be compared exactly.
  static std::unique_ptr<Renderer> phantomRenderer() {
    auto r = std::make_unique<Renderer>(kWidth, kHeight, 0);
    setCase(*r, model(), texture());
    return r;
  }
  static Camera camera(ClinicalView view, const Renderer& r, const RenderOptions& o = {}) {
    return clinicalCamera(view, model().spec.frame, model().tissue.skin.vertices, r.viewAspect(o));
  }

  static Eigen::Vector3i pixel(const RgbImage& img, int x, int y) {
    const unsigned char* p = img.pixels.data() + 3 * (static_cast<size_t>(y) * img.width + x);
    return {p[0], p[1], p[2]};
  }
  static bool isBackground(const RgbImage& img, int x, int y, const RenderOptions& o = {}) {
    return (pixel(img, x, y).cast<double>() - 255.0 * o.background.cast<double>()).cwiseAbs().maxCoeff() <= 1.0;
  }
  static bool covered(const std::vector<float>& depth, int x, int y) {
    return depth[static_cast<size_t>(y) * kWidth + x] < 1.0f;
  }
  // Covered pixels whose 8 neighbours are covered too: away from the silhouette.
  static bool inside(const std::vector<float>& depth, int x, int y) {
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int u = x + dx, v = y + dy;
        if (u < 0 || v < 0 || u >= kWidth || v >= kHeight || !covered(depth, u, v)) return false;
      }
    return true;
  }

 private:
  static inline std::filesystem::path* dir_ = nullptr;
  static inline CaseModel* model_ = nullptr;
  static inline RgbImage* texture_ = nullptr;
};

}  // namespace orthosim::render::test
