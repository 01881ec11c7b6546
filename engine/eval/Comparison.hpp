#pragma once
// `orthosim compare`: a predicted skin against a reference surface - the surface error over the
// whole skin and over the face region, and the soft-tissue landmark errors - and its JSON.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "eval/ErrorSummary.hpp"
#include "eval/FaceRegion.hpp"
#include "eval/LandmarkError.hpp"
#include "eval/SurfaceError.hpp"

namespace orthosim {

struct ComparisonInput {
  const SurfaceMesh* predicted = nullptr;
  const SurfaceMesh* reference = nullptr;
  // From a case (all optional): the rest skin, its landmarks and frame.
  const SurfaceMesh* restSkin = nullptr;
  const Landmarks* landmarks = nullptr;
  AnatomicalFrame frame;
  FaceRegionOptions region;
};

struct Comparison {
  SurfaceError error;
  ErrorSummary whole;
  bool hasRegion = false;
  std::string regionNote;      // the region in words, or why there is none
  std::vector<char> inRegion;  // per predicted vertex; empty without a region
  ErrorSummary region;
  std::vector<LandmarkError> landmarks;  // softTissueLandmarkNames(), when a case is given
};

// The region is judged at rest (on the rest skin's vertices) when the predicted surface is the
// rest skin deformed, so that every prediction of a case is measured on the same skin; else on the
// predicted vertices. Throws std::invalid_argument for a bad surface (see measureSurfaceError).
Comparison compareSurfaces(const ComparisonInput& input);

nlohmann::json comparisonJson(const Comparison& c);

}  // namespace orthosim
