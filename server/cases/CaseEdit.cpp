#include "cases/CaseEdit.hpp"

#include <unistd.h>

#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "scene/CaseFile.hpp"
#include "scene/CaseImport.hpp"
#include "scene/LandmarkFrame.hpp"
#include "system/AtomicFile.hpp"

namespace orthosim::server {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

json cutJson(const CutChoice& c) {
  if (c.kind == "usso" && c.side != "left" && c.side != "right")
    throw CaseEditError("cuts: usso needs its side, \"left\" or \"right\"");
  json cut = {{"template", c.kind}, {"bone", boneOfTemplate(c.kind == "usso" ? "usso_" + c.side : c.kind)}};
  if (c.offsetMm >= 0) cut["offset_mm"] = c.offsetMm;
  if (!c.side.empty()) cut["side"] = c.side;
  if (c.tiltDeg != 0) cut["tilt_deg"] = c.tiltDeg;
  return cut;
}

}  // namespace

void applyCaseEdit(const fs::path& caseFile, const CaseEdit& edit) {
  json root;
  try {
    std::ifstream in(caseFile);
    root = json::parse(in);
  } catch (const std::exception& e) {
    throw CaseEditError("cannot read " + caseFile.string() + ": " + e.what());
  }
  // The landmarks go inline, all of them: one file, renamed into place, holds the whole edit.
  Landmarks landmarks = loadCaseFile(caseFile.string()).landmarks;
  for (const auto& [name, p] : edit.landmarks) {
    if (!p.allFinite() || p.norm() > 1000) throw CaseEditError("landmarks." + name + ": not a point of the head (mm)");
    landmarks[name] = p;
  }
  // A moved porion or orbitale moves the Frankfort horizontal: the frame follows it.
  bool frameMoved = false;
  for (const std::string& name : frankfortLandmarks()) frameMoved = frameMoved || edit.landmarks.count(name);
  if (frameMoved) {
    try {
      if (const std::optional<AnatomicalFrame> f = frameFromLandmarks(landmarks)) {
        auto vec = [](const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); };
        root["frame"] = {{"anterior", vec(f->anterior)}, {"superior", vec(f->superior)}, {"right", vec(f->right)}};
      }
    } catch (const std::invalid_argument& e) {
      throw CaseEditError(std::string("frame: ") + e.what());
    }
  }
  json inline_ = json::object();
  for (const auto& [name, p] : landmarks) inline_[name] = {p.x(), p.y(), p.z()};
  root["landmarks"] = inline_;
  if (edit.cuts) {
    json cuts = json::array();
    try {
      for (const CutChoice& c : *edit.cuts) cuts.push_back(cutJson(c));
    } catch (const CaseImportError& e) {
      throw CaseEditError(e.what());
    }
    root["cuts"] = cuts;
  }
  try {
    // Beside the case file, hidden; removed whatever fails (a full disk, a cut the case refuses).
    AtomicFile file(caseFile, ".case.json.editing-");
    file.out() << root.dump(2) + "\n";
    file.finish();
    const fs::path tmp = file.temporaryPath();
    try {
      loadCaseFile(tmp.string());  // every cut placed from its landmarks, or the reason why not
    } catch (const std::exception& e) {
      std::string why = e.what();
      const std::string prefix = tmp.string() + ": ";
      if (why.rfind(prefix, 0) == 0) why = why.substr(prefix.size());
      throw CaseEditError(why);
    }
    file.commit();  // atomic: a reader sees the old case or the new one
  } catch (const AtomicFileError& e) {
    std::cerr << "orthosim serve: editing a case: " << e.what() << "\n";
    throw CaseEditError("the case file could not be written on the server: " + e.reason());
  }
}

}  // namespace orthosim::server
