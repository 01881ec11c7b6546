#include "scene/CaseImport.hpp"

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <variant>

#include "io/LabelMapSurfaces.hpp"
#include "io/SurfaceImport.hpp"
#include "mesh/PointsInside.hpp"
#include "mesh/SurfaceCheck.hpp"
#include "mesh/SurfaceDistance.hpp"
#include "mesh/SurfacePieces.hpp"
#include "meshing/SurfaceRules.hpp"
#include "scene/CaseFile.hpp"
#include "scene/CaseModel.hpp"
#include "scene/CaseTissue.hpp"
#include "scene/LandmarkFrame.hpp"
#include "scene/LandmarkName.hpp"
#include "scene/MouthGeometry.hpp"
#include "scene/OralCavity.hpp"
#include "scene/Osteotomy.hpp"
#include "scene/SuggestedLandmarks.hpp"
#include "system/FolderInMessage.hpp"
#include "system/TemporaryName.hpp"
#include "volume/DicomSeries.hpp"

namespace orthosim {
namespace {
namespace fs = std::filesystem;
using nlohmann::json;

void stage(const CaseImportInput& in, const char* what) {
  if (in.progress) in.progress(what);
}

// A bone may touch the skin (a thin chin), not pass through it.
constexpr double kOutsideTolerance = 0.5;  // mm

std::string where(const Eigen::Vector3d& p, int digits = 1) {
  std::ostringstream o;
  o.precision(digits);
  o << std::fixed << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return o.str();
}

double scaleFor(const std::string& units, const SurfaceMesh& skin, const std::string& skinPath) {
  if (units == "mm") return 1.0;
  if (units == "m") return 1000.0;
  if (units != "auto") throw CaseImportError("units: '" + units + "' is not one of auto, mm, m");
  const double extent = (skin.vertices.rowwise().maxCoeff() - skin.vertices.rowwise().minCoeff()).maxCoeff();
  if (extent < 1.0)  // a head is 150-300 mm across
    throw CaseImportError(skinPath + ": it is " + std::to_string(extent) +
                          " units across, which looks like metres: pass units m to scale by 1000 (or units mm "
                          "if it really is millimetres)");
  return 1.0;
}

SurfaceMesh readSurface(const std::string& path) {
  try {
    return importSurface(path);
  } catch (const std::exception& e) {
    throw CaseImportError(e.what());
  }
}

// `mesh` as read from `path`, scaled to mm and checked (repairs listed in `warnings`): a cavity as it is,
// skin and bones repaired by the rule the solve applies too (meshing/SurfaceRules).
SurfaceMesh checked(SurfaceMesh mesh, const std::string& path, double scale,
                    const std::variant<SurfaceRequirement, SurfaceRole>& rule, std::vector<std::string>& warnings) {
  mesh.vertices *= scale;
  try {
    const SurfaceReport report = std::holds_alternative<SurfaceRole>(rule)
                                     ? repairAndCheck(mesh, path, std::get<SurfaceRole>(rule))
                                     : checkSurface(mesh, path, std::get<SurfaceRequirement>(rule));
    warnings.insert(warnings.end(), report.warnings.begin(), report.warnings.end());
    if (!report.unitSuspicion.empty()) throw CaseImportError(path + ": " + report.unitSuspicion);
  } catch (const CaseImportError&) {
    throw;
  } catch (const std::exception& e) {
    throw CaseImportError(e.what());
  }
  return mesh;
}

// Every vertex of `inner` inside `skin`, or within kOutsideTolerance of it.
void requireInside(const SurfaceMesh& skin, const PointsInside& inSkin, const SurfaceMesh& inner,
                   const std::string& path) {
  const std::vector<bool> inside = inSkin(inner.vertices);
  std::vector<int> out;
  for (int i = 0; i < inner.numVertices(); ++i)
    if (!inside[i]) out.push_back(i);
  if (out.empty()) return;
  Eigen::Matrix3Xd p(3, out.size());
  for (size_t k = 0; k < out.size(); ++k) p.col(k) = inner.vertices.col(out[k]);
  const Eigen::VectorXd d = distancesToSurface(skin.vertices, skin.triangles, p);
  Eigen::Index worst = 0;
  const double farthest = d.maxCoeff(&worst);
  if (farthest <= kOutsideTolerance) return;
  const long count = (d.array() > kOutsideTolerance).count();
  std::ostringstream o;
  o.precision(1);
  o << std::fixed << path << ": " << count << " of " << inner.numVertices() << " vertices lie outside the skin (up to "
    << farthest << " mm, e.g. at " << where(p.col(worst))
    << "): is it the right file, in the same frame and units as the skin?";
  throw CaseImportError(o.str());
}

// A cavity may open through the skin (the mouth slit: the phantom's oral cavity ends in front of
// the lips), but one wholly outside it is the wrong file or frame.
void requirePartlyInside(const PointsInside& inSkin, const SurfaceMesh& cavity, const std::string& path) {
  const std::vector<bool> inside = inSkin(cavity.vertices);
  if (std::find(inside.begin(), inside.end(), true) == inside.end())
    throw CaseImportError(path +
                          ": the cavity lies wholly outside the skin: is it the right file, in the same "
                          "frame and units as the skin?");
}

// The skin, skull and mandible as read (not yet scaled or checked), each with the name that messages
// give it: the surface files, or the label map's regions.
struct Sources {
  SurfaceMesh skin, skull, mandible;
  std::string skinName, skullName, mandibleName;
  bool fromLabelMap = false;     // in a patient frame (LPS): a label map's or a scan's
  std::string labelMapNote;      // the voxels and their placement, for the user
  std::vector<SurfaceMesh> air;  // from a scan: the air inside the face, piece by piece
  std::vector<std::string> scanNotes;
};

std::string labelList(const std::vector<int>& labels) {
  std::string out;
  for (int l : labels) out += (out.empty() ? "" : ", ") + std::to_string(l);
  return out;
}

// A CT or CBCT series read, segmented, and its labels turned into surfaces.
Sources readScan(const CaseImportInput& in) {
  Sources s;
  DicomReadReport read;
  CtSegmentation seg;
  try {
    DicomReadOptions options;
    options.seriesUid = in.dicomSeries;
    if (in.scanVolume && in.scanRead) {
      read = *in.scanRead;
      stage(in, "segmenting");
      seg = segmentCt(*in.scanVolume, in.segmentation);
    } else {
      stage(in, "reading the series");
      const CtVolume volume = readDicomSeries(in.dicom, options, &read);
      stage(in, "segmenting");
      seg = segmentCt(volume, in.segmentation);
    }
  } catch (const DicomError& e) {
    throw CaseImportError(e.what());
  } catch (const std::invalid_argument& e) {
    throw CaseImportError(in.dicom + ": segmentation: " + e.what());
  }
  s.scanNotes.push_back(in.dicom + ": " + read.summary);
  for (const std::string& w : read.warnings) s.scanNotes.push_back(in.dicom + ": " + w);
  for (const std::string& n : seg.notes) s.scanNotes.push_back("segmentation: " + n);
  using C = CtSegmentation;
  const std::vector<int> present = seg.labels.labels();
  std::vector<LabelRegion> regions = {
      {"skin", present, true}, {"skull", {C::kSkull}, false}, {"mandible", {C::kMandible}, false}};
  const bool air = std::binary_search(present.begin(), present.end(), int(C::kAir));
  if (air) regions.push_back({"air", {C::kAir}, false});
  try {
    seg.labels.path = in.dicom;
    stage(in, "making the surfaces");
    const std::vector<SurfaceMesh> surfaces = labelMapSurfaces(seg.labels, regions);
    s.skin = surfaces[0];
    s.skull = surfaces[1];
    s.mandible = surfaces[2];
    if (air) s.air = surfacePieces(surfaces[3]);
  } catch (const LabelMapError& e) {
    throw CaseImportError(e.what());
  }
  s.skinName = in.dicom + " (skin)";
  s.skullName = in.dicom + " (skull)";
  s.mandibleName = in.dicom + " (mandible)";
  s.fromLabelMap = true;
  return s;
}

Sources readSources(const CaseImportInput& in) {
  const bool surfaces = !in.skin.empty() || !in.skull.empty() || !in.mandible.empty();
  if (!in.dicom.empty() && (surfaces || !in.labelMap.empty()))
    throw CaseImportError(in.dicom + ": give a DICOM series, a label map or the three surfaces, one of them");
  if (!in.dicom.empty()) return readScan(in);
  Sources s;
  if (!in.labelMap.empty() && surfaces)
    throw CaseImportError(in.labelMap + ": give either a label map or the skin, skull and mandible surfaces, not both");
  if (in.labelMap.empty()) {
    for (const auto& [path, what] : {std::pair{&in.skin, "skin"}, {&in.skull, "skull"}, {&in.mandible, "mandible"}})
      if (path->empty())
        throw CaseImportError(std::string("no ") + what +
                              " surface given: give the skin, skull and mandible surfaces, or a label map");
    s.skin = readSurface(in.skin);  // read once: its size tells the units
    s.skull = readSurface(in.skull);
    s.mandible = readSurface(in.mandible);
    s.skinName = in.skin;
    s.skullName = in.skull;
    s.mandibleName = in.mandible;
    return s;
  }
  std::vector<int> all = in.tissueLabels;
  all.insert(all.end(), in.skullLabels.begin(), in.skullLabels.end());
  all.insert(all.end(), in.mandibleLabels.begin(), in.mandibleLabels.end());
  for (const auto& [labels, what] :
       {std::pair{&in.tissueLabels, "soft tissue"}, {&in.skullLabels, "skull"}, {&in.mandibleLabels, "mandible"}})
    if (labels->empty()) throw CaseImportError(in.labelMap + ": no label chosen for the " + what);
  for (size_t a = 0; a < all.size(); ++a)
    for (size_t b = a + 1; b < all.size(); ++b)
      if (all[a] == all[b])
        throw CaseImportError(in.labelMap + ": label " + std::to_string(all[a]) +
                              " is chosen twice (soft tissue, skull and mandible need labels of their own)");
  try {
    const LabelMap map = readLabelMap(in.labelMap);
    const std::vector<int> present = map.labels();
    for (const auto& [labels, what] :
         {std::pair{&in.tissueLabels, "soft tissue"}, {&in.skullLabels, "skull"}, {&in.mandibleLabels, "mandible"}})
      for (int label : *labels)
        if (!std::binary_search(present.begin(), present.end(), label))
          throw CaseImportError(in.labelMap + ": label " + std::to_string(label) + " (chosen for the " + what +
                                ") is not in the label map; its labels are " +
                                (present.empty() ? std::string("none") : labelList(present)));
    const std::vector<SurfaceMesh> surfaces =
        labelMapSurfaces(map, {{"skin (the outer boundary of all tissue labels)", all, true},
                               {"skull", in.skullLabels, false},
                               {"mandible", in.mandibleLabels, false}});
    s.skin = surfaces[0];
    s.skull = surfaces[1];
    s.mandible = surfaces[2];
    std::ostringstream note;
    note.precision(3);
    const Eigen::Vector3d h = map.spacing();
    note << in.labelMap << ": " << map.size[0] << " x " << map.size[1] << " x " << map.size[2] << " voxels of " << h[0]
         << " x " << h[1] << " x " << h[2] << " mm, placed by " << map.orientation << "; surfaces of "
         << s.skin.numTriangles() << " (skin), " << s.skull.numTriangles() << " (skull) and "
         << s.mandible.numTriangles() << " (mandible) triangles";
    s.labelMapNote = note.str();
  } catch (const LabelMapError& e) {
    throw CaseImportError(e.what());
  }
  s.skinName = in.labelMap + " (skin: labels " + labelList(all) + ")";
  s.skullName = in.labelMap + " (skull: labels " + labelList(in.skullLabels) + ")";
  s.mandibleName = in.labelMap + " (mandible: labels " + labelList(in.mandibleLabels) + ")";
  s.fromLabelMap = true;
  return s;
}

json readLandmarks(const std::string& path, double scale) {
  std::ifstream in(path);
  if (!in) throw CaseImportError(path + ": cannot read the landmarks file");
  json j;
  try {
    in >> j;
  } catch (const std::exception& e) {
    throw CaseImportError(path + ": not JSON: " + e.what());
  }
  const auto scaled = [&](json group, const std::string& at) {
    if (!group.is_object()) throw CaseImportError(path + at + ": must be an object of name: [x, y, z]");
    int n = 0;
    for (auto& [name, p] : group.items()) {
      ++n;
      if (!isLandmarkName(name))
        throw CaseImportError(path + at + ": landmark " + std::to_string(n) +
                              "'s name is not 1-64 letters, digits, _ or - (rename it in the file)");
      if (!p.is_array() || p.size() != 3 || !p[0].is_number() || !p[1].is_number() || !p[2].is_number())
        throw CaseImportError(path + at + "." + name + ": must be [x, y, z]");
      for (auto& c : p) c = c.get<double>() * scale;
    }
    return group;
  };
  if (j.is_object() && (j.contains("hard") || j.contains("soft"))) {
    for (const char* g : {"hard", "soft"})
      if (j.contains(g)) j[g] = scaled(j[g], std::string(": ") + g);
    return j;
  }
  return scaled(j, "");
}

json vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

Landmarks flatten(const json& j) {
  Landmarks out;
  const auto add = [&](const json& group) {
    for (const auto& [name, p] : group.items()) out[name] = Eigen::Vector3d(p[0], p[1], p[2]);
  };
  if (j.contains("hard") || j.contains("soft")) {
    for (const char* g : {"hard", "soft"})
      if (j.contains(g)) add(j[g]);
  } else {
    add(j);
  }
  return out;
}

// The patient frame of DICOM (LPS) as the anatomical frame of a label map's surfaces.
AnatomicalFrame lpsFrame() {
  AnatomicalFrame f;
  f.anterior = Eigen::Vector3d(0, -1, 0);
  f.superior = Eigen::Vector3d(0, 0, 1);
  f.right = f.anterior.cross(f.superior);
  return f;
}

// `frame`: none for the case format's default (the files' axes).
json caseJson(const CaseImportInput& in, const std::string& name, const json& cavities, bool landmarks,
              const std::optional<AnatomicalFrame>& frame) {
  json tissue = {{"skin", "skin.obj"}};
  if (!cavities.empty()) tissue["cavities"] = cavities;
  if (!in.texture.empty()) tissue["texture"] = "texture" + fs::path(in.texture).extension().string();
  json cuts = json::array();
  for (const std::string& name : in.cuts) {
    // A unilateral split names its side: usso_left, usso_right.
    const bool usso = name == "usso_left" || name == "usso_right";
    json cut = {{"template", usso ? "usso" : name}, {"bone", boneOfTemplate(name)}};
    if (usso) cut["side"] = name.substr(5);
    cuts.push_back(cut);
  }
  json c = {{"units", "mm"},
            {"name", name},
            {"tissue", tissue},
            {"bones",
             {{{"name", "skull"}, {"surface", "skull.stl"}, {"fixed", true}},
              {{"name", "mandible"}, {"surface", "mandible.stl"}}}},
            {"cuts", cuts},
            // Lips and cheeks slide on the teeth and bone of both jaws; tissue deeper than 30 mm
            // below the skin (the floor of the mouth, the tongue: attached to the mandible in a
            // patient) does not. The phantom's depth: its lips lie within 16 mm of the skin, its
            // cheeks within 28 mm, its floor of the mouth 35-41 mm (docs/scene-format.md).
            {"contact", {{{"bones", {"mandible", "skull"}}, {"range_mm", 15}, {"max_depth_mm", 30}}}}};
  if (landmarks) c["landmarks"] = "landmarks.json";
  if (frame)
    c["frame"] = {{"anterior", vec(frame->anterior)}, {"superior", vec(frame->superior)}, {"right", vec(frame->right)}};
  return c;
}

// The frame the case will have: as given (the other axis from the defaults), else the landmarks'
// Frankfort horizontal, else the label map's patient frame; none for the files' axes (the case
// format's default).
std::optional<AnatomicalFrame> caseFrame(const CaseImportInput& in, const std::optional<AnatomicalFrame>& fromLandmarks,
                                         bool fromLabelMap) {
  const AnatomicalFrame defaults = fromLabelMap ? lpsFrame() : AnatomicalFrame();
  if (!in.anterior && !in.superior) {
    if (fromLandmarks) return fromLandmarks;
    if (fromLabelMap) return defaults;
    return std::nullopt;
  }
  AnatomicalFrame f;
  f.anterior = in.anterior.value_or(defaults.anterior).normalized();
  f.superior = in.superior.value_or(defaults.superior).normalized();
  if (std::abs(f.anterior.dot(f.superior)) > 1e-6)
    throw CaseImportError("frame: anterior " + where(f.anterior) + " and superior " + where(f.superior) +
                          " must be orthogonal");
  f.right = f.anterior.cross(f.superior);
  return f;
}

// Whether the scan already has air between the incisors' edges (outside the skin, whose lips are
// apart, or in a cavity of its own), saying where; none for closed lips, or without the incisors.
std::optional<std::string> mouthHasAir(const Landmarks& landmarks, const PointsInside& inSkin,
                                       const std::vector<SurfaceMesh>& air) {
  const auto upper = landmarks.find("upper_incisor_tip"), lower = landmarks.find("lower_incisor_tip");
  if (upper == landmarks.end() || lower == landmarks.end()) return std::nullopt;
  const Eigen::Vector3d between = 0.5 * (upper->second + lower->second);
  if (!inSkin(Eigen::Matrix3Xd(between))[0])
    return "the lips are apart: the air between the incisors at " + where(between) + " is outside the skin";
  for (const SurfaceMesh& piece : air)
    if (PointsInside(piece)(Eigen::Matrix3Xd(between))[0])
      return "the mouth has air between the incisors at " + where(between) + ", a cavity of the scan";
  return std::nullopt;
}

// Closed lips and teeth in occlusion, as scans have them, with no cavity given: the oral cavity is
// built (scene/OralCavity) so that each lip follows its own jaw. None when it is not built; what was
// found and built goes to `report.built`.
std::optional<SurfaceMesh> autoOralCavity(const CaseImportInput& in, const SurfaceMesh& skin, const SurfaceMesh& skull,
                                          const SurfaceMesh& mandible, const Landmarks& landmarks,
                                          const AnatomicalFrame& frame, const PointsInside& inSkin,
                                          const std::vector<SurfaceMesh>& air, CaseImportReport& report) {
  if (!in.cavities.empty() || in.oralCavity == "none") return std::nullopt;
  if (const std::optional<std::string> open = mouthHasAir(landmarks, inSkin, air)) {
    report.built.push_back("no oral cavity built: " + *open);
    return std::nullopt;
  }
  MouthGeometryInput mi;
  mi.skin = &skin, mi.skull = &skull, mi.mandible = &mandible, mi.landmarks = &landmarks, mi.frame = frame;
  const MouthGeometry mouth = findMouth(mi);
  if (!mouth.teethFound) {
    report.built.push_back("no oral cavity built (" + mouth.note +
                           "): the tissue between the jaws moves with both; give the oral cavity as a file if the "
                           "mouth has air");
    return std::nullopt;
  }
  OralCavity cavity;
  try {
    cavity = fitOralCavity(mouth, frame);
  } catch (const std::exception& e) {
    throw CaseImportError(std::string("oral cavity: ") + e.what());
  }
  requirePartlyInside(inSkin, cavity.surface, "the built oral cavity");
  report.built.push_back(cavity.note);
  return cavity.surface;
}

// A scan's air pieces kept as cavities, but not those the built oral cavity reaches (the mouth's own
// air, which it replaces): two cavities must not cross.
std::vector<SurfaceMesh> airApartFrom(const std::vector<SurfaceMesh>& air, const std::optional<SurfaceMesh>& oral,
                                      const std::string& scan, CaseImportReport& report) {
  if (!oral) return air;
  constexpr double kApartMm = 2.0;
  const PointsInside inOral(*oral);
  std::vector<SurfaceMesh> kept;
  for (const SurfaceMesh& piece : air) {
    const std::vector<bool> inside = inOral(piece.vertices);
    const bool crosses = std::find(inside.begin(), inside.end(), true) != inside.end() ||
                         distancesToSurface(oral->vertices, oral->triangles, piece.vertices).minCoeff() < kApartMm;
    if (!crosses) {
      kept.push_back(piece);
      continue;
    }
    std::ostringstream o;
    o.precision(1);
    o << std::fixed << scan << ": the air of " << std::abs(piece.signedVolume()) / 1000
      << " cm3 at the mouth left to the built oral cavity";
    report.built.push_back(o.str());
  }
  return kept;
}

// Landmarks placed by rules on the surfaces, grouped as a landmarks file is; what was placed and
// what was not goes to `report.suggested`.
json suggested(const SurfaceMesh& skin, const SurfaceMesh& skull, const SurfaceMesh& mandible,
               const AnatomicalFrame& frame, CaseImportReport& report) {
  SuggestedLandmarks s;
  try {
    s = suggestLandmarks(skin, skull, mandible, frame);
  } catch (const std::invalid_argument& e) {
    report.suggested.push_back(std::string("no landmarks suggested: ") + e.what());
    return json::object();
  }
  json out = {{"hard", json::object()}, {"soft", json::object()}};
  std::string names;
  for (const auto& [group, marks] : {std::pair{"hard", &s.hard}, {"soft", &s.soft}})
    for (const auto& [name, p] : *marks) {
      out[group][name] = vec(p);
      names += (names.empty() ? "" : ", ") + name;
    }
  report.suggested.push_back(std::to_string(s.hard.size() + s.soft.size()) +
                             " landmarks placed by rules on the surfaces, to confirm or move: " + names);
  report.suggested.insert(report.suggested.end(), s.notes.begin(), s.notes.end());
  return out;
}

void writeFolder(const CaseImportInput& in, Sources sources, const fs::path& dir, double scale,
                 CaseImportReport& report) {
  std::vector<std::string>& w = report.warnings;
  stage(in, "checking and repairing the surfaces");
  const SurfaceMesh skin = checked(std::move(sources.skin), sources.skinName, scale, SurfaceRole::Skin, w);
  const SurfaceMesh skull = checked(std::move(sources.skull), sources.skullName, scale, SurfaceRole::Bone, w);
  const SurfaceMesh mandible = checked(std::move(sources.mandible), sources.mandibleName, scale, SurfaceRole::Bone, w);
  const PointsInside inSkin(skin);
  requireInside(skin, inSkin, skull, sources.skullName);
  requireInside(skin, inSkin, mandible, sources.mandibleName);
  std::optional<AnatomicalFrame> fromLandmarks;
  json landmarks;
  if (!in.landmarks.empty()) {
    landmarks = readLandmarks(in.landmarks, scale);
    try {
      fromLandmarks = frameFromLandmarks(flatten(landmarks));
    } catch (const std::invalid_argument& e) {
      throw CaseImportError(in.landmarks + ": " + e.what());
    }
    if (fromLandmarks && !in.anterior && !in.superior)
      report.frame = "from the Frankfort horizontal (porions, orbitale): anterior " +
                     where(fromLandmarks->anterior, 3) + ", superior " + where(fromLandmarks->superior, 3);
  }
  if (report.frame.empty())
    report.frame = in.anterior || in.superior ? "as given"
                   : sources.fromLabelMap     ? "the " + std::string(in.dicom.empty() ? "label map" : "scan") +
                                                "'s patient frame (LPS: anterior -y, superior +z)"
                                          : "the files' axes (anterior -x, superior +z)";
  json cavities = json::array();
  for (size_t k = 0; k < in.cavities.size(); ++k) {
    const SurfaceMesh cavity =
        checked(readSurface(in.cavities[k]), in.cavities[k], scale, SurfaceRequirement::Closed, w);
    requirePartlyInside(inSkin, cavity, in.cavities[k]);
    const std::string file = "cavity_" + std::to_string(k) + ".stl";
    exportSurface(cavity, (dir / file).string());
    cavities.push_back(file);
  }
  const std::optional<AnatomicalFrame> frame = caseFrame(in, fromLandmarks, sources.fromLabelMap);
  stage(in, "placing the landmarks and the oral cavity");
  if (in.landmarks.empty()) landmarks = suggested(skin, skull, mandible, frame.value_or(AnatomicalFrame()), report);
  const Landmarks flat = flatten(landmarks);
  const std::optional<SurfaceMesh> oral =
      autoOralCavity(in, skin, skull, mandible, flat, frame.value_or(AnatomicalFrame()), inSkin, sources.air, report);
  std::vector<SurfaceMesh> found = airApartFrom(sources.air, oral, in.dicom, report);
  if (oral) found.push_back(*oral);
  for (size_t k = 0; k < found.size(); ++k) {
    const std::string name = k + 1 == found.size() && oral ? std::string("the built oral cavity")
                                                           : in.dicom + " (air " + std::to_string(k + 1) + ")";
    const SurfaceMesh cavity = checked(found[k], name, 1.0, SurfaceRequirement::Closed, w);
    requirePartlyInside(inSkin, cavity, name);
    const std::string file = "cavity_" + std::to_string(cavities.size()) + ".stl";
    exportSurface(cavity, (dir / file).string());
    cavities.push_back(file);
  }
  stage(in, "writing the case");
  exportSurface(skin, (dir / "skin.obj").string());  // OBJ keeps the texture coordinates
  exportSurface(skull, (dir / "skull.stl").string());
  exportSurface(mandible, (dir / "mandible.stl").string());
  if (!in.texture.empty()) {
    std::error_code ec;
    fs::copy_file(in.texture, dir / ("texture" + fs::path(in.texture).extension().string()), ec);
    if (ec) throw CaseImportError(in.texture + ": cannot copy the texture: " + ec.message());
  }
  const bool anyLandmark = !flat.empty();
  if (anyLandmark) std::ofstream(dir / "landmarks.json") << landmarks.dump(2);
  std::ofstream out(dir / "case.json");
  out << caseJson(in, in.name, cavities, anyLandmark, frame).dump(2) << "\n";
  out.close();
  if (!out) throw CaseImportError((dir / "case.json").string() + ": cannot write the case file");
  try {
    loadCaseFile((dir / "case.json").string());
  } catch (const std::exception& e) {
    throw CaseImportError(std::string("the imported case does not load: ") + e.what());
  }
}

}  // namespace

std::string boneOfTemplate(const std::string& kind) {
  const std::vector<std::string>& known = osteotomyTemplates();
  if (kind == "usso") throw CaseImportError("cuts: 'usso' needs its side: usso_left or usso_right");
  if (kind != "usso_left" && kind != "usso_right" && std::find(known.begin(), known.end(), kind) == known.end()) {
    std::string list;
    for (const std::string& k : known)
      list += (list.empty() ? "" : ", ") + (k == "usso" ? std::string("usso_left, usso_right") : k);
    throw CaseImportError("cuts: unknown osteotomy template '" + kind + "' (templates: " + list + ")");
  }
  return kind == "le_fort_1" || kind == "le_fort_2" || kind == "segmented_maxilla" ? "skull" : "mandible";
}

namespace {

// What opening the case does first: its coarse model built (the tissue meshed around the bones,
// the osteotomies cut, the bonds found), then the caller's own checks. `folder` (the temporary
// one) is left out of messages: they name the case's files as the user knows them.
void checkOpens(const CaseImportInput& input, const std::string& caseFile, const std::string& folder) {
  stage(input, "building the model");
  // The written files by the names the user gave them: "texture.jpg" -> ".../skin.jpg".
  std::vector<std::pair<std::string, std::string>> given = {
      {"skin.obj", input.skin}, {"skull.stl", input.skull}, {"mandible.stl", input.mandible}};
  if (!input.texture.empty())
    given.push_back({"texture" + fs::path(input.texture).extension().string(), input.texture});
  const auto named = [&](std::string message) {
    message = withoutFolder(std::move(message), folder);
    for (const auto& [written, user] : given) {
      if (user.empty()) continue;
      for (std::size_t at = 0; (at = message.find(written, at)) != std::string::npos;) {
        if (at == 0 || message[at - 1] == ' ' || message[at - 1] == '\'') {
          message.replace(at, written.size(), user);
          at += user.size();
        } else {
          at += written.size();
        }
      }
    }
    return message;
  };
  try {
    CaseTissueOptions options;
    options.cacheDir = input.cacheDir.empty() ? defaultCacheDir() : input.cacheDir;
    (void)buildCaseModel(loadCaseFile(caseFile), Resolution::Coarse, options);
    if (input.opens) input.opens(caseFile);
  } catch (const std::exception& e) {
    throw CaseImportError("the case would not open: " + named(e.what()));
  }
}

}  // namespace

CaseImportReport importCase(const CaseImportInput& input, const std::string& outDir) {
  const fs::path out = fs::absolute(outDir);
  if (fs::exists(out)) throw CaseImportError(out.string() + ": exists already; choose a new folder for the case");
  for (const std::string& kind : input.cuts) boneOfTemplate(kind);  // unknown templates before any work
  if (input.oralCavity != "auto" && input.oralCavity != "none")
    throw CaseImportError("oral_cavity: '" + input.oralCavity + "' is not one of auto, none");
  CaseImportInput named = input;
  if (named.name.empty()) named.name = out.filename().string();
  Sources sources = readSources(input);
  CaseImportReport report;
  report.scale = scaleFor(input.units, sources.skin, sources.skinName);
  report.labelMap = sources.labelMapNote;
  report.scan = sources.scanNotes;
  // Written beside its place and renamed into it: a folder with case.json is always complete.
  const fs::path tmp = out.parent_path() / ("." + out.filename().string() + ".importing-" + temporarySuffix());
  fs::remove_all(tmp);
  fs::create_directories(tmp);
  try {
    writeFolder(named, std::move(sources), tmp, report.scale, report);
    if (input.checkOpens) checkOpens(input, (tmp / "case.json").string(), tmp.string() + "/");
    fs::rename(tmp, out);
  } catch (...) {
    std::error_code ignored;
    fs::remove_all(tmp, ignored);
    throw;
  }
  report.caseFile = (out / "case.json").string();
  return report;
}

}  // namespace orthosim
