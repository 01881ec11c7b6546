// Planning from the face: landmark probes, the landmark Jacobian against finite
// differences of nonlinear solves, the round trip from a plan's predicted face back to its poses
// (contact on and off), unreachable targets and bad input.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <memory>

#include "eval/LandmarkError.hpp"
#include "phantom/PhantomCase.hpp"
#include "planning/LandmarkJacobian.hpp"
#include "planning/PlanFromFace.hpp"
#include "scene/CaseModel.hpp"
#include "solver/PlanSolver.hpp"

namespace orthosim {
namespace {

using Poses = std::map<std::string, AnatomicalPose>;

CaseSpec phantomSpec() {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("orthosim_face_test_" + std::to_string(::getpid()));
  CaseSpec spec = loadCaseFile(writePhantomCase(0, (dir / "case").string()));
  return spec;
}

struct Phantom {
  std::unique_ptr<CaseModel> coarse;
  std::unique_ptr<Model> model;
  std::vector<PlanningFragment> fragments;

  explicit Phantom(bool contact) {
    CaseSpec spec = phantomSpec();
    if (!contact) spec.contacts.clear();
    coarse = std::make_unique<CaseModel>(buildCaseModel(spec, Resolution::Coarse, {ORTHOSIM_TEST_CACHE_DIR}));
    model = std::make_unique<Model>(coarse->scene);
    fragments = planningFragments(*coarse);
  }
  SimState solve(const Poses& poses) { return solve(poses, model->restState()); }
  SimState solve(const Poses& poses, const SimState& from) {
    const SolveResult r =
        solvePlan(*model, from, model->targetsFromPlan(planFromPoses(fragments, poses, coarse->spec.frame), from),
                  model->scene().solver);
    EXPECT_TRUE(r.converged) << r.error;
    return r.state;
  }
  // The fragments the face does not show (the proximal segments of a split): locked.
  std::vector<PoseLock> lockAllBut(const std::vector<std::string>& names) const {
    std::vector<PoseLock> out;
    for (const PlanningFragment& f : fragments)
      if (std::find(names.begin(), names.end(), f.name) == names.end())
        for (int k = 0; k < 6; ++k) out.push_back({f.name, k});
    return out;
  }
};

Poses knownPlan() {
  Poses p;
  p["maxilla"] = {4.0, 2.0, 0.0, 2.0, 0.0, 0.0};    // Le Fort I: 4 mm advance, 2 mm up, 2 degrees front up
  p["mandible"] = {3.0, 1.0, 0.5, -1.5, 1.0, 1.0};  // BSSO: advance with a small asymmetric turn
  return p;
}

TEST(LandmarkProbe, FollowsTheSkinAsTheEvaluationPlacesIt) {
  const Phantom p(true);
  const std::vector<std::string> names = skinLandmarkNames(*p.coarse);
  for (const char* n : {"pronasale", "subnasale", "labrale_superius", "stomion", "soft_pogonion"})
    EXPECT_NE(std::find(names.begin(), names.end(), n), names.end()) << n;
  EXPECT_EQ(std::find(names.begin(), names.end(), "pogonion"), names.end()) << "a bone landmark";
  const std::vector<LandmarkProbe> probes = landmarkProbes(*p.coarse, names);
  Eigen::Matrix3Xd x = p.coarse->scene.mesh.rest;
  for (int i = 0; i < x.cols(); ++i) x.col(i) += Eigen::Vector3d(0.01 * x(2, i), std::sin(0.05 * x(0, i)), 0.3);
  const SurfaceMesh moved = p.coarse->deformedSkin(x);
  const std::vector<LandmarkError> e =
      landmarkErrors(names, p.coarse->spec.landmarks, p.coarse->spec.frame, {p.coarse->tissue.skin, moved, moved});
  for (size_t i = 0; i < names.size(); ++i) {
    EXPECT_LT((probes[i].rest - p.coarse->spec.landmarks.at(names[i])).norm(), kMaxLandmarkSkinOffsetMm);
    EXPECT_LT((probes[i].at(x) - e[i].predicted).norm(), 1e-9) << names[i];
  }
}

TEST(LandmarkProbe, RefusesABoneOrUnknownLandmark) {
  const Phantom p(false);
  try {
    landmarkProbes(*p.coarse, {"pogonion"});
    FAIL() << "a bone landmark was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("pogonion"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("not a soft-tissue landmark"), std::string::npos);
  }
  EXPECT_THROW(landmarkProbes(*p.coarse, {"glabella_soft"}), std::invalid_argument);
}

// Each column against central differences of converged nonlinear solves (h = 0.05 mm or degree).
void checkJacobian(bool contact) {
  Phantom p(contact);
  const std::vector<LandmarkProbe> probes = landmarkProbes(*p.coarse, skinLandmarkNames(*p.coarse));
  const Poses base = knownPlan();
  const SimState s = p.solve(base);
  const Eigen::MatrixXd J = landmarkJacobian(*p.model, p.coarse->spec.frame, p.fragments, probes, s, base);
  ASSERT_EQ(J.cols(), 6 * static_cast<Eigen::Index>(p.fragments.size()));
  const double h = 0.05;
  double worst = 0, scale = 0;
  for (const char* name : {"maxilla", "mandible"}) {
    const size_t f = std::find_if(p.fragments.begin(), p.fragments.end(),
                                  [&](const PlanningFragment& x) { return x.name == name; }) -
                     p.fragments.begin();
    ASSERT_LT(f, p.fragments.size()) << name;
    for (int k : {0, 1, 3, 4, 5}) {  // the right shift is checked by the round trip
      Poses plus = base, minus = base;
      Eigen::Matrix<double, 6, 1> vp = base.at(name).values(), vm = vp;
      vp[k] += h, vm[k] -= h;
      plus[name] = AnatomicalPose::fromValues(vp), minus[name] = AnatomicalPose::fromValues(vm);
      const SimState sp = p.solve(plus, s), sm = p.solve(minus, s);
      for (size_t i = 0; i < probes.size(); ++i) {
        const Eigen::Vector3d fd = (probes[i].at(sp.x) - probes[i].at(sm.x)) / (2 * h);
        const Eigen::Vector3d col =
            J.block<3, 1>(3 * static_cast<Eigen::Index>(i), 6 * static_cast<Eigen::Index>(f) + k);
        worst = std::max(worst, (fd - col).norm());
        scale = std::max(scale, fd.norm());
      }
    }
  }
  EXPECT_GT(scale, 0.5) << "the landmarks do move with the bones";
  EXPECT_LT(worst, 0.02 * scale) << "largest column error " << worst << " mm per unit, columns up to " << scale;
  std::cout << "largest column error " << worst << " mm per mm or degree, columns up to " << scale << "\n";
}

TEST(LandmarkJacobian, MatchesFiniteDifferencesOfSolvesWithoutContact) { checkJacobian(false); }
TEST(LandmarkJacobian, MatchesFiniteDifferencesOfSolvesWithContact) { checkJacobian(true); }

// From rest to the predicted landmarks of a known plan: the plan's poses again.
void roundTrip(bool contact, const Poses& plan) {
  Phantom p(contact);
  const SimState solved = p.solve(plan);
  if (contact) EXPECT_GT(p.model->activeContacts(solved).size(), 0u) << "the lips press on the teeth";
  const std::vector<std::string> names = skinLandmarkNames(*p.coarse);
  const std::vector<LandmarkProbe> probes = landmarkProbes(*p.coarse, names);
  std::vector<FaceTarget> targets;
  for (const LandmarkProbe& probe : probes) targets.push_back({probe.name, {}, probe.at(solved.x), 1.0});
  FaceFitOptions options;
  options.locks = p.lockAllBut({"maxilla", "mandible"});
  int reports = 0;
  const FaceFitResult r = planFromFace(*p.model, *p.coarse, p.fragments, targets, {}, options, {},
                                       [&](const FaceFitProgress&) { ++reports; });
  EXPECT_TRUE(r.reached) << r.message;
  EXPECT_GT(reports, 1);
  double worst = 0;
  for (const auto& [name, want] : plan) {
    const Eigen::Matrix<double, 6, 1> got = r.poses.at(name).values(), w = want.values();
    for (int k = 0; k < 6; ++k) {  // mm, then degrees
      EXPECT_NEAR(got[k], w[k], 0.2) << name << " " << poseComponentName(k);
      worst = std::max(worst, std::abs(got[k] - w[k]));
    }
  }
  for (const TargetResidual& t : r.residuals) EXPECT_LT(t.distance(), 0.05) << t.landmark;
  std::cout << "round trip (contact " << contact << "): " << r.iterations << " iterations, " << r.solves << " solves, "
            << r.seconds << " s, poses off by at most " << worst << " mm or degrees; " << r.message << "\n";
}

// A class III correction: the mandible set back 6 mm, which presses the lower lip on the teeth.
Poses setbackPlan() {
  Poses p;
  p["maxilla"] = {2.0, 0.0, 0.0, 1.0, 0.0, 0.0};
  p["mandible"] = {-6.0, 1.0, -0.5, 1.5, -1.0, 1.0};
  return p;
}

TEST(PlanFromFace, RecoversAKnownPlanFromItsFaceWithoutContact) { roundTrip(false, knownPlan()); }
TEST(PlanFromFace, RecoversASetbackFromItsFaceWithLipsOnTheTeeth) { roundTrip(true, setbackPlan()); }

TEST(PlanFromFace, ABoneLimitSaysSoAndGivesTheBestPoses) {
  Phantom p(false);
  FaceFitOptions options;
  options.locks = p.lockAllBut({"mandible"});
  for (int k = 1; k < 6; ++k) options.locks.push_back({"mandible", k});  // only its advancement is free
  options.translationLimitMm = 5;                                        // as a server with a 5 mm limit holds it
  const FaceFitResult r = planFromFace(*p.model, *p.coarse, p.fragments, {{"soft_pogonion", {12, 0, 0}}}, {}, options);
  EXPECT_FALSE(r.reached);
  EXPECT_NEAR(r.poses.at("mandible").anteriorMm, 5.0, 1e-9);
  ASSERT_FALSE(r.atLimit.empty());
  EXPECT_NE(r.message.find("mandible anterior_mm at +5"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("soft_pogonion"), std::string::npos) << r.message;
  EXPECT_GT(r.residuals[0].distance(), 2.0);
}

TEST(PlanFromFace, AFitWithEveryValueFreeStaysWithinTheLimitsInBoundedWork) {
  Phantom p(false);
  FaceFitOptions options;
  options.locks = p.lockAllBut({"mandible"});
  options.translationLimitMm = 5;
  options.rotationLimitDeg = 5;
  const FaceFitResult r = planFromFace(*p.model, *p.coarse, p.fragments, {{"soft_pogonion", {15, 0, 0}}}, {}, options);
  std::cout << r.iterations << " iterations, " << r.solves << " solves, " << r.seconds << " s: " << r.message << "\n";
  EXPECT_FALSE(r.reached);
  EXPECT_FALSE(r.atLimit.empty());
  // The fit goes as far as the limits let it (a translation ends on its 5 mm bound, which the clamp
  // alone would not reach) and brings the chin closer than it was (15 mm away at rest).
  const Eigen::Matrix<double, 6, 1> v = r.poses.at("mandible").values();
  EXPECT_NEAR(v.head<3>().cwiseAbs().maxCoeff(), 5.0, 1e-6) << v.transpose();
  EXPECT_LE(v.tail<3>().cwiseAbs().maxCoeff(), 5.0 + 1e-9);
  EXPECT_LT(r.residuals[0].distance(), 12.0);
  EXPECT_LT(r.solves, 60) << "each refused trial is a solve: the fit must not wander";
}

TEST(PlanFromFace, ConflictingTargetsSaySoAndCompromiseByWeight) {
  Phantom p(false);
  FaceFitOptions options;
  options.locks = p.lockAllBut({"mandible"});
  for (int k = 1; k < 6; ++k) options.locks.push_back({"mandible", k});  // only its advancement is free
  // The chin forward and the lower lip back: one advancement cannot do both.
  const std::vector<FaceTarget> targets{{"soft_pogonion", {4, 0, 0}, {}, 1.0},
                                        {"labrale_inferius", {-4, 0, 0}, {}, 1.0}};
  const FaceFitResult r = planFromFace(*p.model, *p.coarse, p.fragments, targets, {}, options);
  EXPECT_FALSE(r.reached);
  EXPECT_TRUE(r.atLimit.empty());
  EXPECT_NE(r.message.find("conflict"), std::string::npos) << r.message;
  EXPECT_LT(std::abs(r.poses.at("mandible").anteriorMm), 2.0) << "an even compromise stays near rest";
  std::vector<FaceTarget> chinFirst = targets;
  chinFirst[0].weight = 10;
  const FaceFitResult w = planFromFace(*p.model, *p.coarse, p.fragments, chinFirst, {}, options);
  EXPECT_GT(w.poses.at("mandible").anteriorMm, r.poses.at("mandible").anteriorMm + 1.0)
      << "a heavier chin target pulls the compromise its way";
}

TEST(PlanFromFace, RefusesBadInputNamingIt) {
  Phantom p(false);
  const auto refuses = [&](const std::vector<FaceTarget>& targets, const FaceFitOptions& o, const Poses& start,
                           const std::string& words) {
    try {
      planFromFace(*p.model, *p.coarse, p.fragments, targets, start, o);
      ADD_FAILURE() << "accepted; expected: " << words;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  };
  const std::vector<FaceTarget> ok{{"soft_pogonion", {2, 0, 0}}};
  refuses({}, {}, {}, "at least one");
  refuses({{"pogonion", {2, 0, 0}}}, {}, {}, "not a soft-tissue landmark");
  refuses({{"soft_pogonion", {2, 0, 0}, {}, 0.0}}, {}, {}, "weight must be > 0");
  refuses({{"soft_pogonion", {NAN, 0, 0}}}, {}, {}, "not a finite number");
  refuses({{"soft_pogonion", {1, 0, 0}}, {"soft_pogonion", {2, 0, 0}}}, {}, {}, "a second target");
  FaceFitOptions all;
  all.locks = p.lockAllBut({});
  refuses(ok, all, {}, "every pose value is locked");
  FaceFitOptions unknown;
  unknown.locks = {{"zygoma", 0}};
  refuses(ok, unknown, {}, "no fragment zygoma");
  refuses(ok, {}, {{"maxilla", {40, 0, 0, 0, 0, 0}}}, "beyond the limit");
}

}  // namespace
}  // namespace orthosim
