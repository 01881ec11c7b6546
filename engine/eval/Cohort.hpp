#pragma once
// The synthetic cohort of the accuracy evaluation: ten phantom patients (M1-M10) mirroring the procedure mix of the
// paper's Table 1 (Le Fort I with and without segmentation, one Le Fort II, BSSO and USSO, one
// genioplasty, class II / III / asymmetry / open bite morphologies, one case without maxillary
// surgery), and two large class III setbacks, where the lips press on the teeth (M11: 10 mm BSSO setback alone;
// M12: 5 mm Le Fort I advancement and 8 mm BSSO setback), each a phantom variant with its osteotomies and a plan of
// clinically usual magnitudes (../shared/notes/clinical-primer.md: 2-10 mm, up to 5-10 degrees). Frame of the phantom:
// mm, +x posterior, +y right, +z superior (advancement is -x, impaction +z). Each fragment's motion is its own world
// motion: a genioplasty piece that rides on a moved mandible has the mandible's rotation and centre plus its own
// translation.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace orthosim {

struct CohortMotion {
  std::string fragment;
  double translation[3] = {0, 0, 0};  // mm, case frame
  double rotationDeg[3] = {0, 0, 0};  // axis-angle, degrees (about +x: roll, +y: pitch, +z: yaw)
  // Rotation centre: the mean of these landmarks (e.g. both condylia); empty: the origin.
  std::vector<std::string> centerLandmarks;
};

struct CohortPatient {
  std::string id;         // M1..M10 as in the paper's Table 1, then M11, M12
  std::string diagnosis;  // class II, class III, asymmetry, open bite
  int variant = 0;        // phantom variant (engine/phantom): 1 class II, 2 class III, 3 asymmetry, 4 open bite
  std::string maxilla;    // "Le Fort I", "Le Fort I segmented", "Le Fort II", "none"
  std::string mandible;   // "BSSO", "USSO", "none"
  bool genioplasty = false;
  std::vector<nlohmann::json> cuts;  // case-file cuts (docs/scene-format.md)
  std::vector<CohortMotion> plan;
  std::string procedure() const;  // short label, e.g. "LF1 seg + BSSO"
};

// The patients that mirror the paper's Table 1 come first; the setbacks follow.
constexpr size_t kTableOnePatients = 10;

const std::vector<CohortPatient>& cohortPatients();

// Writes the patient's phantom under dir (writePhantomCase) and replaces its case's cuts and plan
// with the patient's; returns the case file's path. Throws std::runtime_error naming a landmark
// the phantom lacks or a file that cannot be written.
std::string writeCohortCase(const CohortPatient& patient, const std::string& dir);

}  // namespace orthosim
