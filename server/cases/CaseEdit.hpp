#pragma once
// Changing an imported patient's landmarks and osteotomies from the page: the new landmarks
// and cuts are written into a copy of its case.json, which is loaded as a
// check (every cut placed from its landmarks) and only then renamed over the case file. A moved
// porion or orbitale re-derives the anatomical frame (scene/LandmarkFrame). A refused edit leaves
// the case as it was.
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "scene/Osteotomy.hpp"

namespace orthosim::server {

struct CutChoice {
  std::string kind;      // a template (osteotomyTemplates())
  double offsetMm = -1;  // the template's level; < 0: its default
  std::string side;      // usso only: "left" or "right"
  double tiltDeg = 0;    // le_fort_1, segmented_maxilla, genioplasty: + raises the cut's front
};

struct CaseEdit {
  Landmarks landmarks;                         // set or moved (mm, at rest); the others stay
  std::optional<std::vector<CutChoice>> cuts;  // replaces the case's cuts when given
};

struct CaseEditError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Applies `edit` to the case file. Throws CaseEditError with what is wrong (a cut that needs a
// landmark the case lacks, an unknown template, a landmark outside the head's reach of 1 m).
void applyCaseEdit(const std::filesystem::path& caseFile, const CaseEdit& edit);

}  // namespace orthosim::server
