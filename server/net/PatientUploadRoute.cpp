#include "net/PatientUploadRoute.hpp"

#include <algorithm>
#include <boost/asio/post.hpp>

#include "cases/Identifier.hpp"
#include "net/JsonResponses.hpp"
#include "net/RequestTarget.hpp"
#include "net/ScanRoutes.hpp"
#include "scene/CaseImport.hpp"

namespace orthosim::net {
namespace {

std::vector<std::string> commaList(const std::string& s) {
  std::vector<std::string> out;
  std::size_t from = 0;
  for (std::size_t comma; from <= s.size(); from = comma + 1) {
    comma = s.find(',', from);
    if (comma == std::string::npos) comma = s.size();
    std::string item = s.substr(from, comma - from);
    item.erase(0, item.find_first_not_of(' '));
    item.erase(item.find_last_not_of(' ') + 1);
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

// "1, 4" -> {1, 4}: label numbers of a label map, each 1..65535.
std::vector<int> labelNumbers(const std::string& field, const std::string& text) {
  std::vector<int> out;
  for (const std::string& item : commaList(text)) {
    std::size_t used = 0;
    int value = 0;
    try {
      value = std::stoi(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != item.size() || value < 1 || value > 65535)
      throw server::PatientImportError("bad_field", field,
                                       field + ": '" + item + "' is not a label number (1 to 65535)");
    out.push_back(value);
  }
  return out;
}

}  // namespace

bool isPatientUpload(const Request& request) {
  if (request.method() != http::verb::post) return false;
  const std::optional<RequestTarget> target =
      parseRequestTarget(std::string_view(request.target().data(), request.target().size()));
  return target && target->path == kPatientsPath;
}

void checkCutTemplates(const std::vector<std::string>& cuts) {
  for (const std::string& cut : cuts) try {
      boneOfTemplate(cut);
    } catch (const std::exception& e) {  // names the template and the known ones
      throw server::PatientImportError("bad_field", "cuts", e.what());
    }
}

server::PatientUpload patientUploadFromForm(const UploadRequest& request, const std::vector<FormPartSpan>& parts) {
  using server::PatientImportError;
  server::PatientUpload upload;
  for (const FormPartSpan& p : parts) {
    if (server::isUploadField(p.name)) {
      upload.files.push_back({p.name, p.fileName, formFile(request, p)});
      continue;
    }
    if (!p.fileName.empty())
      throw PatientImportError("bad_field", p.name, p.name + ": a file in a field that takes none");
    const std::string text = formText(request, p);
    if (p.name == "id") {
      upload.id = text;
    } else if (p.name == "name") {
      if (text.size() > 200) throw PatientImportError("bad_field", "name", "name: longer than 200 characters");
      upload.name = text;
    } else if (p.name == "units") {
      upload.units = text;
    } else if (p.name == "oral_cavity") {
      upload.oralCavity = text;
    } else if (p.name == "cuts") {
      for (const std::string& cut : commaList(text)) upload.cuts.push_back(cut);
      checkCutTemplates(upload.cuts);
    } else if (server::isScanChoiceField(p.name)) {
      server::setScanChoiceField(upload.scan, p.name, text);
    } else if (p.name == "tissue_labels" || p.name == "skull_labels" || p.name == "mandible_labels") {
      std::vector<int>& labels = p.name == "tissue_labels"  ? upload.tissueLabels
                                 : p.name == "skull_labels" ? upload.skullLabels
                                                            : upload.mandibleLabels;
      labels = labelNumbers(p.name, text);
    } else {
      throw PatientImportError(
          "bad_field", p.name,
          p.name +
              ": no such field (id, name, units, oral_cavity, cuts, skin, skull, mandible, label_map, "
              "tissue_labels, skull_labels, mandible_labels, cavity, texture, landmarks, dicom, dicom_zip, series, "
              "skin_threshold, bone_threshold, mandible_seed, skull_seed)");
    }
  }
  // A browser sends an empty part for a file input left empty: that is no file.
  upload.files.erase(
      std::remove_if(upload.files.begin(), upload.files.end(),
                     [](const server::UploadedFile& f) { return f.fileName.empty() && f.bytes.size == 0; }),
      upload.files.end());
  return upload;
}

void importPatient(server::PlanningService& service, UploadRequest request, std::function<void(StringResponse)> done) {
  boost::asio::post(service.importPool(), [&service, request = std::move(request), done = std::move(done)]() mutable {
    const ReplyTo to = replyTo(request.head);
    StringResponse reply;
    try {
      const std::vector<FormPartSpan> parts = formParts(request);
      const server::ImportedPatient imported = service.patients().import(patientUploadFromForm(request, parts));
      reply = jsonResponse(http::status::created, importedJson(imported), to);
    } catch (const server::PatientImportError& e) {
      reply = importErrorReply(e, kPatientsPath, to);
    } catch (const std::exception& e) {
      reply = importFailureReply(e, kPatientsPath, to);
    }
    request.body.reset();  // the body file and the slot go before the client hears
    done(std::move(reply));
  });
}

}  // namespace orthosim::net
