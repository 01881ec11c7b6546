#include "eval/Cohort.hpp"

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "phantom/PhantomCase.hpp"
#include "scene/CaseFile.hpp"
#include "system/AtomicFile.hpp"

namespace orthosim {
namespace {

using nlohmann::json;

json cut(const char* tmpl, const char* bone, const char* side = nullptr) {
  json c = {{"template", tmpl}, {"bone", bone}};
  if (side) c["side"] = side;
  return c;
}

CohortMotion move(const char* fragment, double ap, double si, double lr, double roll = 0, double pitch = 0,
                  double yaw = 0, std::vector<std::string> center = {}) {
  // ap: advancement (+) / setback (-); si: impaction (+) / downgraft (-); lr: towards the right (+).
  CohortMotion m;
  m.fragment = fragment;
  m.translation[0] = -ap;
  m.translation[1] = lr;
  m.translation[2] = si;
  m.rotationDeg[0] = roll;
  m.rotationDeg[1] = pitch;
  m.rotationDeg[2] = yaw;
  m.centerLandmarks = std::move(center);
  return m;
}

// The three segments of a segmented Le Fort I moved together, the posterior ones `expand` mm apart
// each (arch widening).
std::vector<CohortMotion> segmented(double ap, double si, double expand) {
  return {move("maxilla_anterior", ap, si, 0), move("maxilla_left", ap, si, -expand),
          move("maxilla_right", ap, si, expand)};
}

std::vector<CohortMotion> join(std::vector<CohortMotion> a, const std::vector<CohortMotion>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

std::vector<CohortPatient> makeCohort() {
  std::vector<CohortPatient> c;
  const auto add = [&](const char* id, const char* dx, int variant, const char* mx, const char* md, bool genio,
                       std::vector<json> cuts, std::vector<CohortMotion> plan) {
    CohortPatient p;
    p.id = id, p.diagnosis = dx, p.variant = variant, p.maxilla = mx, p.mandible = md, p.genioplasty = genio;
    p.cuts = std::move(cuts), p.plan = std::move(plan);
    c.push_back(std::move(p));
  };
  // Class III: maxillary advancement with arch expansion, mandibular setback.
  add("M1", "class III", 2, "Le Fort I segmented", "BSSO", false,
      {cut("segmented_maxilla", "skull"), cut("bsso", "mandible")},
      join(segmented(4, 0, 1.5), {move("mandible", -5, 0, 0)}));
  // Open bite: posterior impaction (the maxilla pitched counter-clockwise), mandibular autorotation
  // forward and up.
  add("M2", "open bite", 4, "Le Fort I segmented", "BSSO", false,
      {cut("segmented_maxilla", "skull"), cut("bsso", "mandible")},
      join(segmented(2, 2, 1.0), {move("mandible", 3, 2, 0)}));
  add("M3", "class III", 2, "Le Fort II", "BSSO", false, {cut("le_fort_2", "skull"), cut("bsso", "mandible")},
      {move("maxilla", 5, 0, 0), move("mandible", -4, 0, 0)});
  // Asymmetry (chin 7 mm to the right): midline correction of the maxilla, the mandible turned
  // about its unsplit left condyle (yaw +3 degrees brings the chin about 4 mm to the left), the chin
  // piece riding on it and brought 2 mm further left and 3 mm forward.
  add("M4", "asymmetry", 3, "Le Fort I", "USSO", true,
      {cut("le_fort_1", "skull"), cut("usso", "mandible", "right"), cut("genioplasty", "mandible")},
      {move("maxilla", 0, 0, -2), move("mandible", 0, 0, 0, 0, 0, 3, {"condylion_left"}),
       move("chin", 3, 0, -2, 0, 0, 3, {"condylion_left"})});
  add("M5", "class II", 1, "Le Fort I segmented", "BSSO", false,
      {cut("segmented_maxilla", "skull"), cut("bsso", "mandible")},
      join(segmented(0, 3, 1.0), {move("mandible", 6, 0, 0)}));
  add("M6", "class II", 1, "Le Fort I segmented", "BSSO", false,
      {cut("segmented_maxilla", "skull"), cut("bsso", "mandible")},
      join(segmented(2, 0, 1.5), {move("mandible", 8, 0, 0)}));
  add("M7", "class III", 2, "Le Fort I segmented", "none", false, {cut("segmented_maxilla", "skull")},
      segmented(6, 0, 1.5));
  add("M8", "class III", 2, "Le Fort I segmented", "none", false, {cut("segmented_maxilla", "skull")},
      segmented(4, 2, 2.0));
  // No maxillary surgery: mandibular midline correction, the distal segment turned about the
  // midpoint of the condyles (yaw +3 degrees: the chin about 4 mm to the left) and shifted 2 mm left.
  add("M9", "asymmetry", 3, "none", "BSSO", false, {cut("bsso", "mandible")},
      {move("mandible", 0, 0, -2, 0, 0, 3, {"condylion_left", "condylion_right"})});
  // Occlusal cant corrected by rolling the maxilla, mandible shifted to the midline.
  add("M10", "asymmetry", 3, "Le Fort I", "BSSO", false, {cut("le_fort_1", "skull"), cut("bsso", "mandible")},
      {move("maxilla", 2, 0, 0, 3, 0, 0, {"upper_incisor_tip"}), move("mandible", 2, 0, -3)});
  // Beyond Table 1: large class III setbacks, where the lips press on the teeth. The
  // phantom's contact stays as its case declares it. The phantom's lower incisors are 3.5 mm ahead
  // of the upper ones, so these plans leave them behind: they test the magnitude, not an occlusion.
  add("M11", "class III", 2, "none", "BSSO", false, {cut("bsso", "mandible")}, {move("mandible", -10, 0, 0)});
  add("M12", "class III", 2, "Le Fort I", "BSSO", false, {cut("le_fort_1", "skull"), cut("bsso", "mandible")},
      {move("maxilla", 5, 0, 0), move("mandible", -8, 0, 0)});
  return c;
}

}  // namespace

std::string CohortPatient::procedure() const {
  std::string s;
  if (maxilla == "Le Fort I")
    s = "LF1";
  else if (maxilla == "Le Fort I segmented")
    s = "LF1 seg";
  else if (maxilla == "Le Fort II")
    s = "LF2";
  if (mandible != "none") s += (s.empty() ? "" : " + ") + mandible;
  if (genioplasty) s += (s.empty() ? "" : " + ") + std::string("genio");
  return s;
}

const std::vector<CohortPatient>& cohortPatients() {
  static const std::vector<CohortPatient> cohort = makeCohort();
  return cohort;
}

std::string writeCohortCase(const CohortPatient& patient, const std::string& dir) {
  const std::string path = writePhantomCase(patient.variant, dir);
  const CaseSpec phantom = loadCaseFile(path);
  json c;
  {
    std::ifstream in(path);
    in >> c;
  }
  c["name"] = patient.id + " " + patient.diagnosis + " (" + patient.procedure() + ")";
  c["cuts"] = patient.cuts;
  json plan = json::object();
  for (const CohortMotion& m : patient.plan) {
    json motion = {{"translation_mm", {m.translation[0], m.translation[1], m.translation[2]}},
                   {"rotation_deg", {m.rotationDeg[0], m.rotationDeg[1], m.rotationDeg[2]}}};
    if (!m.centerLandmarks.empty()) {
      Eigen::Vector3d c = Eigen::Vector3d::Zero();
      for (const std::string& name : m.centerLandmarks) {
        const auto it = phantom.landmarks.find(name);
        if (it == phantom.landmarks.end())
          throw std::runtime_error(patient.id + ": the phantom has no landmark '" + name + "'");
        c += it->second / static_cast<double>(m.centerLandmarks.size());
      }
      motion["center_mm"] = {c.x(), c.y(), c.z()};
    }
    plan[m.fragment] = motion;
  }
  c["plan"] = plan;
  writeFileAtomically(path, c.dump(2) + "\n");
  return path;
}

}  // namespace orthosim
