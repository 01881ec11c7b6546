#pragma once
// One solve of a cohort case (engine/eval/Cohort) at a skin resolution and a tolerance scale, and
// its skin measured against a discretisation reference: a finer mesh of the same plan solved to
// tight tolerances (`orthosim bench cohort`).
#include <string>
#include <vector>

#include "eval/ErrorSummary.hpp"
#include "eval/LandmarkError.hpp"
#include "scene/CaseFile.hpp"

namespace orthosim {

// The reference is computed offline: ten times the interactive iteration budget (solver
// max_total_iterations), which tight tolerances with contact can need.
constexpr int kCohortReferenceIterations = 3000;

// The soft-tissue landmarks of Table 4, where a setback shows first: the lower lip, the upper lip
// and the soft chin (names of softTissueLandmarkNames(); labels as in cephalometry).
struct CohortTableLandmark {
  std::string name, label;
};
const std::vector<CohortTableLandmark>& cohortTableLandmarks();  // labrale_inferius Li, labrale_superius Ls,
                                                                 // soft_pogonion Pog'

// A mesh resolution and a tolerance scale (1: the solver's defaults, 1e-4 E h^2 and 1e-4 h).
struct CohortRunConfig {
  std::string label;
  int skinTriangles = 0;
  double toleranceScale = 1.0;
  int maxTotalIterations = 0;  // 0: the scene's budget (the product's, for interactive solves)
};

struct CohortRun {
  CohortRunConfig config;
  int skinTriangles = 0, tets = 0, nodes = 0;
  double buildSeconds = 0, solveSeconds = 0;  // solveSeconds: the median of solveTimes
  std::vector<double> solveTimes;
  int iterations = 0, chordIterations = 0;
  std::vector<std::string> warnings;  // the solve's, about its result (crushed tissue)
  SurfaceMesh rest, skin;             // the case's full-resolution skin at rest and deformed
  CaseSpec spec;
  // Against the reference (not for the reference itself):
  bool measured = false;
  ErrorSummary region;
  std::vector<LandmarkError> landmarks;
  double shareWithin(size_t threshold) const { return region.shareWithin.at(threshold); }
  // mm from the run's landmark to the reference's (the same skin point); NaN when not measured.
  double landmarkErrorMm(const std::string& name) const;
};

// Builds the case's model at the configured resolution (tissue cache in cacheDir) and solves its
// plan `repeats` times. Throws std::runtime_error naming the case and run when a solve fails.
CohortRun solveCohortRun(const CaseSpec& base, const CohortRunConfig& config, int repeats, const std::string& cacheDir);

// The run's face-region error and landmark errors against the reference's skin. Every run carries
// the case's full-resolution skin (CaseModel::deformedSkin), so a landmark is the same skin point on
// both, placed once on the rest skin: skin sliding along the profile counts, not only the distance
// across it. Throws std::runtime_error when the case gives no face region, or the reference's skin
// has other triangles than the run's.
void measureAgainst(CohortRun& run, const CohortRun& reference);

}  // namespace orthosim
