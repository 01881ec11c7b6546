#pragma once
// Osteotomies as the surgeon plans them: planes, or parametric templates (Le Fort I and II,
// three-piece segmented maxilla, bilateral and unilateral sagittal split, genioplasty) placed on
// a case's bony landmarks. A cut turns part of a bone into a named fragment: the region inside all
// of its bounding planes. The rest of the bone stays the bone's own fragment.
#include <Eigen/Core>
#include <map>
#include <string>
#include <vector>

#include "scene/CutBlend.hpp"

namespace orthosim {

// Anatomical directions of a case, unit and orthogonal (the phantom and the ArtiSynth face both
// use +x posterior, +y right, +z superior).
struct AnatomicalFrame {
  Eigen::Vector3d anterior{-1, 0, 0};
  Eigen::Vector3d superior{0, 0, 1};
  Eigen::Vector3d right{0, 1, 0};
};

using Landmarks = std::map<std::string, Eigen::Vector3d>;

// A fragment cut from `parent` (a bone, or a fragment an earlier cut made): the points of the
// parent for which every bound's signed distance is >= 0 (normals point into the fragment).
struct FragmentRegion {
  std::string name;
  std::string parent;
  std::vector<CutPlane> bounds;

  bool contains(const Eigen::Vector3d& x) const;
};

struct OsteotomySpec {
  std::string kind;              // a template name (osteotomyTemplates()) or "planes"
  std::string bone;              // the bone (or earlier fragment) it cuts
  std::string side;              // "left" or "right": unilateral sagittal split only
  std::string fragment;          // "planes": the name of the fragment cut off
  std::vector<CutPlane> planes;  // "planes": its bounds
  double offset = -1;            // mm, the template's level (see osteotomyRegions); < 0: the default
  double tilt = 0;               // degrees the level cut turns about the right axis, + raising its front
};

// Whether a template's level cut can be tilted (le_fort_1, segmented_maxilla, genioplasty).
bool osteotomyTilts(const std::string& kind);

// Template names: le_fort_1, le_fort_2, segmented_maxilla, bsso, usso, genioplasty.
const std::vector<std::string>& osteotomyTemplates();

// The landmarks a template places its cut from (usso: both sides' names, as either may be cut), so
// that a page can ask for them before the case is cut. Throws std::invalid_argument for an unknown
// template.
const std::vector<std::string>& osteotomyLandmarks(const std::string& kind);

// The fragments a cut makes, in order (a later region wins where two overlap). Templates and their
// landmarks (frame directions A, S, R; offsets in mm):
//  le_fort_1:  "maxilla": below the plane `offset` (4) above upper_incisor_apex, within 12 mm outside the
//              upper first molars (upper_molar_*), anterior of the
//              coronal plane 5 behind PNS (the pterygomaxillary junction).
//  le_fort_2:  "maxilla": below a gable through a point `offset` (8) below nasion whose sides fall
//              40 degrees laterally (nasal bones, orbital floor, zygomaticomaxillary region), and
//              anterior of the PNS plane, within the same lateral limits.
//  segmented_maxilla: Le Fort I split by planes between canine and first premolar on each side
//              (upper_canine_*, upper_molar_*): "maxilla_anterior", "maxilla_left", "maxilla_right".
//  bsso:       "ramus_left", "ramus_right": proximal segments behind a coronal plane `offset` (12)
//              behind lower_molar_* on each side; the tooth-bearing rest keeps the bone's name.
//  usso:       the same on `side` only.
//  genioplasty: "chin": below the plane `offset` (5) under the mental foramina, rising 10 degrees
//              anteriorly, anterior of a coronal plane 15 behind the lower canines.
// Throws std::invalid_argument naming a missing landmark, an unknown template or side, a plane
// whose normal is not unit length or finite.
std::vector<FragmentRegion> osteotomyRegions(const OsteotomySpec& cut, const Landmarks& landmarks,
                                             const AnatomicalFrame& frame = {});

}  // namespace orthosim
