// The prediction band on the coarse phantom: the band contains the nominal
// prediction (every vertex's envelope and every landmark's range hold 0), and it widens at the lips
// and chin when the parameter ranges grow (range scale 0.5 against 1). The bonded-lips variant
// bonds the contact nodes that touch the bone at rest; the gaps are printed (the measurement
// behind kLipsTouchDistanceMm).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <map>

#include "eval/PredictionBand.hpp"
#include "eval/PredictionBandJson.hpp"
#include "phantom/PhantomCase.hpp"
#include "scene/BondedContact.hpp"

namespace fs = std::filesystem;

namespace orthosim {
namespace {

class PhantomBand : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(fs::temp_directory_path() / ("orthosim_band_" + std::to_string(::getpid())));
    const CaseSpec spec = loadCaseFile(writePhantomCase(0, (*dir_ / "case").string()));
    // The tissue from the build tree's cache: each test runs in a process of its own.
    coarse_ = new CaseModel(buildCaseModel(spec, Resolution::Coarse, {ORTHOSIM_TEST_CACHE_DIR}));
  }
  static void TearDownTestSuite() {
    delete full_;
    delete skins_;
    delete coarse_;
    fs::remove_all(*dir_);
    delete dir_;
  }
  static const CaseModel& coarse() { return *coarse_; }
  // The full band (16 solves), made by the first test that asks: ctest runs each test in a process
  // of its own, and only the band tests need it.
  static const PredictionBand& full() {
    if (!full_) {
      skins_ = new std::map<int, SurfaceMesh>;
      BandControl control;
      control.onSkin = [](int run, const SurfaceMesh& skin) { (*skins_)[run] = skin; };
      full_ = new PredictionBand(predictionBand(*coarse_, coarse_->spec.plan, {}, control));
    }
    return *full_;
  }
  // The skins of the full band's converged runs, by run: the band keeps only their envelope.
  static const std::map<int, SurfaceMesh>& runSkins() {
    full();
    return *skins_;
  }

  // Display-skin vertices within 6 mm of the lips' and chin's landmarks at rest.
  static std::vector<int> lipsAndChin() {
    std::vector<int> out;
    const SurfaceMesh& skin = coarse().tissue.skin;
    for (int i = 0; i < skin.numVertices(); ++i)
      for (const char* name : {"labrale_superius", "labrale_inferius", "soft_pogonion"})
        if ((skin.vertices.col(i) - coarse().spec.landmarks.at(name)).norm() < 6.0) {
          out.push_back(i);
          break;
        }
    return out;
  }

 private:
  static inline fs::path* dir_ = nullptr;
  static inline CaseModel* coarse_ = nullptr;
  static inline PredictionBand* full_ = nullptr;
  static inline std::map<int, SurfaceMesh>* skins_ = nullptr;
};

TEST_F(PhantomBand, ContainsTheNominalPrediction) {
  const PredictionBand& b = full();
  ASSERT_FALSE(b.cancelled);
  ASSERT_EQ(b.runs.size(), b.design.runs.size());
  EXPECT_EQ(b.design.runs.size(), 16u);  // the phantom has lips on its teeth: four parameters
  for (const BandRun& r : b.runs)
    std::cout << r.run.label << ": " << (r.converged ? "converged" : r.error) << ", " << r.seconds << " s\n";
  EXPECT_EQ(b.converged(), 16);
  ASSERT_EQ(b.envelope.low.size(), coarse().tissue.skin.numVertices());
  EXPECT_TRUE(b.envelope.low.allFinite() && b.envelope.high.allFinite());
  EXPECT_GT(b.envelope.width().maxCoeff(), 0.2);  // the parameters do move the face
  // Each landmark's range is the nominal and every converged run's offset, no more and no less:
  // recomputed here from the runs, and wider than the nominal alone for most landmarks.
  int measured = 0, moved = 0;
  for (size_t i = 0; i < b.landmarks.size(); ++i) {
    const LandmarkRange& l = b.landmarks[i];
    if (!l.measured) continue;
    ++measured;
    Eigen::Vector3d low = Eigen::Vector3d::Zero(), high = Eigen::Vector3d::Zero();
    for (const BandRun& r : b.runs)
      if (r.converged && r.landmarkOffsets.at(i)) {
        low = low.cwiseMin(*r.landmarkOffsets[i]);
        high = high.cwiseMax(*r.landmarkOffsets[i]);
      }
    EXPECT_LT((l.low - low).norm(), 1e-12) << l.name;
    EXPECT_LT((l.high - high).norm(), 1e-12) << l.name;
    if ((high - low).maxCoeff() > 0.05) ++moved;
    std::cout << l.name << ": anterior " << l.low.x() << " .. " << l.high.x() << ", superior " << l.low.y() << " .. "
              << l.high.y() << " mm\n";
  }
  EXPECT_GE(measured, 6);
  EXPECT_GE(2 * moved, measured) << "the parameters move most landmarks by more than 0.05 mm";
  // The envelope likewise: at each vertex the least and greatest offset of the nominal and every
  // converged run along the nominal skin's normal, recomputed from the runs' skins.
  const std::map<int, SurfaceMesh>& skins = runSkins();
  ASSERT_EQ(skins.size(), static_cast<size_t>(b.converged()));
  const SurfaceMesh& nominal = skins.at(0);
  ASSERT_EQ(nominal.numVertices(), b.envelope.nominal.numVertices());
  EXPECT_LT((nominal.vertices - b.envelope.nominal.vertices).cwiseAbs().maxCoeff(), 1e-12);
  const Eigen::Matrix3Xd normals = nominal.vertexNormals();
  EXPECT_LT((normals - b.envelope.normals).cwiseAbs().maxCoeff(), 1e-12);
  Eigen::VectorXd low = Eigen::VectorXd::Zero(nominal.numVertices()), high = low;
  for (const auto& [run, skin] : skins) {
    const Eigen::VectorXd offset = (skin.vertices - nominal.vertices).cwiseProduct(normals).colwise().sum();
    low = low.cwiseMin(offset);
    high = high.cwiseMax(offset);
  }
  EXPECT_LT((b.envelope.low - low).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((b.envelope.high - high).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_GT((high - low).maxCoeff(), 0.2) << "the runs' skins differ";
  // Every one-at-a-time effect is there, and the bonded lips moved at least one lip landmark.
  for (size_t p = 0; p < b.effect.size(); ++p)
    for (size_t l = 0; l < b.landmarks.size(); ++l) EXPECT_EQ(b.effect[p][l].has_value(), b.landmarks[l].measured);
  EXPECT_GT(b.lips.bonded, 0);
  EXPECT_LT(b.lips.bonded, b.lips.contactNodes);
  const nlohmann::json j = predictionBandJson(b);
  EXPECT_EQ(j["solves"], 16);
  EXPECT_EQ(j["failed"], 0);
  EXPECT_GT(j["width"]["max_mm"].get<double>(), 0.2);
}

TEST_F(PhantomBand, WidensAtTheLipsAndChinWhenTheRangesGrow) {
  // One at a time only (8 solves each): the corners' contribution is checked by the band above.
  BandOptions whole, half;
  whole.design.corners = half.design.corners = false;
  half.design.rangeScale = 0.5;
  const PredictionBand wider = predictionBand(coarse(), coarse().spec.plan, whole);
  const PredictionBand narrow = predictionBand(coarse(), coarse().spec.plan, half);
  ASSERT_EQ(wider.converged(), static_cast<int>(wider.runs.size()));
  ASSERT_EQ(narrow.converged(), static_cast<int>(narrow.runs.size()));
  const std::vector<int> region = lipsAndChin();
  ASSERT_GT(region.size(), 10u);
  double wide = 0, slim = 0;
  for (int i : region) {
    wide += wider.envelope.width()[i];
    slim += narrow.envelope.width()[i];
  }
  wide /= static_cast<double>(region.size());
  slim /= static_cast<double>(region.size());
  std::cout << "mean band width at the lips and chin: range scale 1 " << wide << " mm, 0.5 " << slim << " mm\n";
  EXPECT_GT(wide, slim * 1.2);
  for (size_t l = 0; l < wider.landmarks.size(); ++l) {
    if (!wider.landmarks[l].measured) continue;
    const double a = (wider.landmarks[l].high - wider.landmarks[l].low).norm();
    const double b = (narrow.landmarks[l].high - narrow.landmarks[l].low).norm();
    const std::string& name = wider.landmarks[l].name;
    if (name == "labrale_inferius" || name == "soft_pogonion" || name == "labrale_superius") EXPECT_GT(a, b) << name;
  }
}

// What "touch" means, measured: the rest gaps of the contact nodes to the nearest bone surface.
TEST_F(PhantomBand, BondedLipsBondOnlyTheNodesThatTouchTheBone) {
  const ContactGaps gaps = contactGaps(coarse().scene);
  std::vector<double> d = gaps.distance;
  std::sort(d.begin(), d.end());
  ASSERT_FALSE(d.empty());
  const auto below = [&](double t) { return std::count_if(d.begin(), d.end(), [&](double x) { return x <= t; }); };
  std::cout << d.size() << " contact nodes; rest gap to the bone: min " << d.front() << ", median " << d[d.size() / 2]
            << ", max " << d.back() << " mm; within 0.1 mm " << below(0.1) << ", 0.5 mm " << below(0.5) << ", 1 mm "
            << below(1.0) << ", 2 mm " << below(2.0) << ", 3 mm " << below(3.0) << "\n";
  Scene scene = coarse().scene;
  const BondedContactReport r = bondTouchingContactNodes(scene, kLipsTouchDistanceMm);
  EXPECT_EQ(r.bonded, below(kLipsTouchDistanceMm));
  int left = 0;
  for (const ContactSpec& c : scene.contacts) left += static_cast<int>(c.nodes.size());
  EXPECT_GT(left, 0);
  for (const ContactSpec& c : scene.contacts)
    for (int n : c.nodes)
      for (const FragmentSpec& f : scene.fragments)
        EXPECT_EQ(std::count(f.nodes.begin(), f.nodes.end(), n), 0) << "node " << n << " both slides and is bonded";
  EXPECT_THROW(bondTouchingContactNodes(scene, -1), std::invalid_argument);
}

// Without a nominal prediction there is no band: said, not an empty envelope.
TEST_F(PhantomBand, ANominalSolveThatFailsIsAnErrorNamingIt) {
  CaseModel starved = coarse();
  // A force tolerance no solve reaches, two iterations a substep and no halving: a quick failure.
  starved.scene.solver.forceTolerance = 1e-30;
  starved.scene.solver.stepTolerance = 1e-30;
  starved.scene.solver.maxIterations = 2;
  starved.scene.solver.maxRefinements = 0;
  try {
    predictionBand(starved, starved.spec.plan);
    FAIL() << "no error";
  } catch (const BandNominalFailed& e) {
    EXPECT_EQ(e.outcome, SolveOutcome::failed) << e.what();
    EXPECT_NE(std::string(e.what()).find("nominal"), std::string::npos) << "names the nominal solve: " << e.what();
  }
}

TEST_F(PhantomBand, CancelStopsAtOnceAndSaysSo) {
  std::atomic<bool> cancel{false};
  BandControl control;
  control.cancel = &cancel;
  int seen = 0;
  control.onProgress = [&](const BandProgress& p) {
    EXPECT_EQ(p.solves, 16);
    if (p.solve >= 2) cancel = true;  // during the second solve
    ++seen;
  };
  const PredictionBand b = predictionBand(coarse(), coarse().spec.plan, {}, control);
  EXPECT_TRUE(b.cancelled);
  EXPECT_EQ(b.runs.size(), 1u);  // the nominal; the second solve stopped within a Newton iteration
  EXPECT_GT(seen, 1);
}

}  // namespace
}  // namespace orthosim
