#pragma once
// The acceptance check for an imported phantom: its Le Fort I prediction (the phantom's own plan)
// against the phantom's, on the face region, and where the plan moved the skin more than 2 mm
// (there the face at rest must be far off, so the comparison can fail).
#include <gtest/gtest.h>

#include <string>

#include "eval/Comparison.hpp"
#include "eval/ErrorSummary.hpp"
#include "scene/CaseFile.hpp"
#include "scene/CaseModel.hpp"
#include "solver/PlanSolver.hpp"

namespace orthosim::test {

struct LeFortIMatch {
  Comparison face;           // the imported case's prediction against the phantom's
  ErrorSummary movedPart;    // where the skin moved more than 2 mm
  ErrorSummary restAtMoved;  // the face at rest there
};

inline LeFortIMatch compareLeFortI(const std::string& phantomCaseFile, const std::string& importedCaseFile) {
  const CaseSpec phantomSpec = loadCaseFile(phantomCaseFile);
  CaseSpec spec = loadCaseFile(importedCaseFile);
  EXPECT_EQ(phantomSpec.plan.size(), 1u);
  spec.plan = phantomSpec.plan;  // the phantom's Le Fort I advancement
  const auto predict = [](const CaseModel& m) {
    Model model(m.scene);
    const SolveResult r = solveScene(model);
    EXPECT_TRUE(r.converged) << r.error;
    return m.deformedSkin(r.state.x);
  };
  // The phantom's tissue from the build tree's cache (the tests run in processes of their own); the
  // imported case is meshed, which is what these tests check.
  const CaseModel phantom = buildCaseModel(phantomSpec, Resolution::Coarse, {ORTHOSIM_TEST_CACHE_DIR});
  const CaseModel patient = buildCaseModel(spec, Resolution::Coarse);
  const SurfaceMesh expected = predict(phantom), predicted = predict(patient);
  ComparisonInput c;
  c.predicted = &predicted;
  c.reference = &expected;
  c.restSkin = &patient.tissue.skin;
  c.landmarks = &spec.landmarks;
  c.frame = spec.frame;
  LeFortIMatch out;
  out.face = compareSurfaces(c);
  c.predicted = &patient.tissue.skin;
  const Comparison rest = compareSurfaces(c);
  std::vector<char> moved = out.face.inRegion;
  for (int i = 0; i < predicted.numVertices(); ++i)
    moved[i] &= (predicted.vertices.col(i) - patient.tissue.skin.vertices.col(i)).norm() > 2.0;
  out.movedPart = summarizeError(out.face.error, moved);
  out.restAtMoved = summarizeError(rest.error, moved);
  return out;
}

// Within 1 mm on 95% of the face region and of the part the plan moved; the plan moved a real part
// of the face, where the rest face is off.
inline void expectSameLeFortI(const LeFortIMatch& m) {
  ASSERT_TRUE(m.face.hasRegion) << m.face.regionNote;
  EXPECT_GE(m.face.region.shareWithin[0], 0.95);
  EXPECT_GE(m.movedPart.shareWithin[0], 0.95);
  EXPECT_GT(m.movedPart.area, 500.0);
  EXPECT_LT(m.restAtMoved.shareWithin[0], 0.5);
}

}  // namespace orthosim::test
