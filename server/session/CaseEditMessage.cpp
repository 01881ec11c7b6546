// `edit_case` (docs/protocol.md): an imported patient's landmarks placed or moved and its
// osteotomies chosen and shifted in the page; the case file is rewritten (cases/CaseEdit) and the
// case opened again, its models rebuilt with progress.
#include <cmath>

#include "cases/CaseEdit.hpp"
#include "scene/LandmarkName.hpp"
#include "session/CaseHandler.hpp"

namespace orthosim::server {
using nlohmann::json;
namespace {

[[noreturn]] void refuse(const std::string& where, const std::string& what) {
  throw ProtocolError("bad_value", where + ": " + what, where);
}

Landmarks readLandmarks(const MessageReader& r, const json& j) {
  if (!j.is_object()) r.fail("bad_value", "must be an object {name: [x, y, z]}", "landmarks");
  Landmarks out;
  for (const auto& [name, value] : j.items()) {
    const std::string where = jsonPointer(r.pointer("landmarks"), name);
    if (!isLandmarkName(name)) refuse(where, "a landmark name is 1-64 letters, digits, _ or -");
    if (!value.is_array() || value.size() != 3 || !value[0].is_number() || !value[1].is_number() ||
        !value[2].is_number())
      refuse(where, "must be [x, y, z] in mm");
    const Eigen::Vector3d p(value[0].get<double>(), value[1].get<double>(), value[2].get<double>());
    if (!p.allFinite()) refuse(where, "must be finite");
    out[name] = p;
  }
  return out;
}

std::vector<CutChoice> readCuts(const MessageReader& r, const json& j) {
  if (!j.is_array()) r.fail("bad_value", "must be an array of {kind, offset_mm?, tilt_deg?, side?}", "cuts");
  std::vector<CutChoice> out;
  for (std::size_t i = 0; i < j.size(); ++i) {
    MessageReader c(j[i], jsonPointer(r.pointer("cuts"), std::to_string(i)));
    CutChoice cut;
    cut.kind = c.string("kind");
    if (c.has("offset_mm")) cut.offsetMm = c.number("offset_mm", 0, 0, 50, "mm");
    if (c.has("tilt_deg")) cut.tiltDeg = c.number("tilt_deg", 0, -30, 30, "degrees");
    if (const std::optional<std::string> side = c.optionalString("side")) cut.side = *side;
    c.rejectUnknown();
    out.push_back(cut);
  }
  return out;
}

}  // namespace

void CaseHandler::editCase(MessageReader& r, const json& id) {
  const std::string caseId = state_.openCaseId();
  const std::optional<CaseEntry> entry = cases_.find(caseId);
  if (!entry || entry->source != "import")
    throw ProtocolError("read_only_case", "case '" + caseId +
                                              "' is not an imported patient: its landmarks and osteotomies are fixed "
                                              "(import the patient to place them)");
  CaseEdit edit;
  if (r.has("landmarks")) edit.landmarks = readLandmarks(r, r.raw()["landmarks"]);
  if (r.has("cuts")) edit.cuts = readCuts(r, r.raw()["cuts"]);
  r.rejectUnknown();
  if (edit.landmarks.empty() && !edit.cuts)
    throw ProtocolError("missing_field", "edit_case needs landmarks or cuts to change", "/landmarks");
  const std::filesystem::path caseFile = entry->caseFile;
  // On the opening pool, as the rebuild that follows: the file written, then the case opened again.
  openings_.submit([this, keep = channel_.keepAlive(), caseId, caseFile, edit, id](const std::atomic<bool>&) {
    try {
      applyCaseEdit(caseFile, edit);
    } catch (const std::exception& e) {
      return channel_.sendError("edit_failed", "case '" + caseId + "' is unchanged: " + e.what(), "", id);
    }
    cases_.invalidate(caseId);
    channel_.reply({{"type", "case_edited"}, {"case", caseId}}, id);
    startOpening(caseId, id);
  });
}

}  // namespace orthosim::server
