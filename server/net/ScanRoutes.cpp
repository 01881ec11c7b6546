#include "net/ScanRoutes.hpp"

#include <boost/asio/post.hpp>
#include <iostream>

#include "cases/CaseCatalog.hpp"
#include "image/RgbImage.hpp"
#include "net/FormBodyFile.hpp"
#include "net/JsonResponses.hpp"
#include "net/MultipartForm.hpp"
#include "net/PatientUploadRoute.hpp"
#include "net/RequestTarget.hpp"
#include "render/PngFile.hpp"
#include "util/ClientText.hpp"
#include "util/Utf8Text.hpp"

namespace orthosim::net {
namespace {

std::optional<std::string> pathOf(const Request& request) {
  const std::optional<RequestTarget> target =
      parseRequestTarget(std::string_view(request.target().data(), request.target().size()));
  if (!target) return std::nullopt;
  return target->path;
}

std::string base64(const std::vector<unsigned char>& bytes) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const unsigned b0 = bytes[i], b1 = i + 1 < bytes.size() ? bytes[i + 1] : 0,
                   b2 = i + 2 < bytes.size() ? bytes[i + 2] : 0;
    const unsigned n = (b0 << 16) | (b1 << 8) | b2;
    out += table[(n >> 18) & 63];
    out += table[(n >> 12) & 63];
    out += i + 1 < bytes.size() ? table[(n >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? table[n & 63] : '=';
  }
  return out;
}

nlohmann::json vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

nlohmann::json previewJson(const server::ScanPreview& p) {
  const CtSegmentation& s = p.segmentation;
  nlohmann::json images = nlohmann::json::array();
  for (const SegmentationSlice& slice : p.slices) {
    RgbImage image;
    image.width = slice.width;
    image.height = slice.height;
    image.pixels = slice.rgb;
    images.push_back({{"plane", slice.plane},
                      {"placed", slice.placed},
                      {"width", slice.width},
                      {"height", slice.height},
                      {"src", "data:image/png;base64," + base64(render::encodePng(image))},
                      {"origin", vec(slice.origin)},
                      {"column", vec(slice.column)},
                      {"row", vec(slice.row)},
                      {"pixels",
                       {{"outside", slice.pixels[0]},
                        {"tissue", slice.pixels[CtSegmentation::kTissue]},
                        {"skull", slice.pixels[CtSegmentation::kSkull]},
                        {"mandible", slice.pixels[CtSegmentation::kMandible]},
                        {"air", slice.pixels[CtSegmentation::kAir]}}}});
  }
  return {{"series", p.series},
          {"read", p.read.summary},
          {"read_warnings", p.read.warnings},
          {"skin_threshold", s.skinThreshold},
          {"bone_threshold", s.boneThreshold},
          {"threshold_source", s.thresholdSource},
          {"mandible_seed", vec(s.mandibleSeed)},
          {"skull_seed", vec(s.skullSeed)},
          {"metal_voxels", s.metalVoxels},
          {"notes", s.notes},
          {"images", images}};
}

// The fields of an import: the case's (id, name, cuts, oral_cavity) and the scan's.
server::PatientUpload uploadFromJson(const nlohmann::json& body) {
  using server::PatientImportError;
  server::PatientUpload upload;
  if (!body.is_object()) throw PatientImportError("bad_request", "", "the body must be a JSON object");
  for (const auto& [key, value] : body.items()) {
    auto text = [&, &key = key, &value = value]() {
      if (!value.is_string()) throw PatientImportError("bad_field", key, key + ": not a string");
      return value.get<std::string>();
    };
    if (key == "id") {
      upload.id = text();
    } else if (key == "name") {
      upload.name = text();
      if (upload.name.size() > 200) throw PatientImportError("bad_field", "name", "name: longer than 200 characters");
    } else if (key == "oral_cavity") {
      upload.oralCavity = text();
    } else if (key == "cuts") {
      if (value.is_string()) {
        std::string list = value.get<std::string>();
        for (std::size_t from = 0, comma; from <= list.size(); from = comma + 1) {
          comma = list.find(',', from);
          if (comma == std::string::npos) comma = list.size();
          std::string cut = list.substr(from, comma - from);
          cut.erase(0, cut.find_first_not_of(' '));
          cut.erase(cut.find_last_not_of(' ') + 1);
          if (!cut.empty()) upload.cuts.push_back(cut);
        }
      } else if (value.is_array()) {
        for (const nlohmann::json& c : value) {
          if (!c.is_string()) throw PatientImportError("bad_field", "cuts", "cuts: not a list of template names");
          upload.cuts.push_back(c.get<std::string>());
        }
      } else {
        throw PatientImportError("bad_field", "cuts", "cuts: not a list of template names");
      }
    } else if (server::isScanChoiceField(key)) {
      server::setScanChoiceField(upload.scan, key, value);
    } else {
      throw PatientImportError("bad_field", key,
                               key +
                                   ": no such field (id, name, cuts, oral_cavity, series, skin_threshold, "
                                   "bone_threshold, mandible_seed, skull_seed)");
    }
  }
  checkCutTemplates(upload.cuts);
  return upload;
}

server::ScanChoice choiceFromJson(const nlohmann::json& body) {
  using server::PatientImportError;
  server::ScanChoice choice;
  if (!body.is_object()) throw PatientImportError("bad_request", "", "the body must be a JSON object");
  for (const auto& [key, value] : body.items()) {
    if (!server::isScanChoiceField(key))
      throw PatientImportError(
          "bad_field", key,
          key + ": no such field (series, skin_threshold, bone_threshold, mandible_seed, skull_seed)");
    server::setScanChoiceField(choice, key, value);
  }
  return choice;
}

nlohmann::json jsonBody(const Request& request) {
  if (request.body().empty()) return nlohmann::json::object();
  try {
    return nlohmann::json::parse(request.body());
  } catch (const nlohmann::json::exception&) {
    throw server::PatientImportError("bad_request", "", "the body is not JSON");
  }
}

bool isHexToken(const std::string& s) {
  if (s.size() != 32) return false;
  for (char c : s)
    if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'))) return false;
  return true;
}

}  // namespace

nlohmann::json seriesJson(const std::vector<DicomSeriesInfo>& series) {
  nlohmann::json out = nlohmann::json::array();
  for (const DicomSeriesInfo& s : series)
    out.push_back({{"uid", s.uid},
                   {"description", s.description},
                   {"modality", s.modality},
                   {"files", s.files},
                   {"rows", s.rows},
                   {"columns", s.columns},
                   {"study_date", s.studyDate}});
  return out;
}

StringResponse importErrorReply(const server::PatientImportError& e, const std::string& path, const ReplyTo& to) {
  nlohmann::json body = {{"error", e.code}, {"message", server::withoutServerPaths(e.what())}, {"path", path}};
  body["field"] = server::quotableUtf8(e.field);
  body["message"] = server::quotableUtf8(body["message"].get<std::string>());
  if (!e.series.empty()) body["series"] = seriesJson(e.series);
  const http::status status = e.code == "case_exists"      ? http::status::conflict
                              : e.code == "unknown_scan"   ? http::status::not_found
                              : e.code == "too_many_scans" ? http::status::service_unavailable
                                                           : http::status::bad_request;
  return jsonResponse(status, body, to);
}

StringResponse importFailureReply(const std::exception& e, const std::string& path, const ReplyTo& to) {
  std::cerr << "orthosim serve: " << path << ": the import failed: " << e.what() << "\n";
  return jsonResponse(http::status::internal_server_error,
                      {{"error", "import_failed"},
                       {"message", "the import failed on the server (its log says why); try again, or report it"},
                       {"path", path},
                       {"field", ""}},
                      to);
}

std::vector<FormPartSpan> formParts(const UploadRequest& request) {
  using server::PatientImportError;
  std::vector<FormPartSpan> parts;
  try {
    const auto type = request.head[http::field::content_type];
    const std::string boundary = formBoundary(std::string_view(type.data(), type.size()));
    FormBodyFile body(request.body->path());
    parts = locateFormParts(body, boundary);
  } catch (const FormError& e) {
    throw PatientImportError("bad_form", "body", server::quotableUtf8(e.what()));
  }
  for (const FormPartSpan& p : parts) {
    if (!server::isUtf8(p.name))
      throw PatientImportError("bad_field", server::quotableUtf8(p.name),
                               server::quotableUtf8(p.name) + ": a field name not valid UTF-8");
    if (!server::isUtf8(p.fileName))
      throw PatientImportError("bad_file", p.name, p.name + ": the file name is not valid UTF-8");
  }
  return parts;
}

std::string formText(const UploadRequest& request, const FormPartSpan& part) {
  constexpr std::uint64_t kMaxFieldBytes = 64 * 1024;
  if (part.size > kMaxFieldBytes)
    throw server::PatientImportError("bad_field", part.name, part.name + ": longer than 64 KiB");
  std::string text = server::readSlice(formFile(request, part));
  if (!server::isUtf8(text)) throw server::PatientImportError("bad_field", part.name, part.name + ": not valid UTF-8");
  return text;
}

server::FileSlice formFile(const UploadRequest& request, const FormPartSpan& part) {
  return {request.body->path(), part.offset, part.size};
}

nlohmann::json importedJson(const server::ImportedPatient& imported) {
  return {{"case", server::casesJson({imported.entry})["cases"][0]},
          {"scale", imported.report.scale},
          {"frame", imported.report.frame},
          {"warnings", imported.report.warnings},
          {"built", imported.report.built},
          {"scan", imported.report.scan},
          {"suggested", imported.report.suggested}};
}

bool isScanUpload(const Request& request) {
  if (request.method() != http::verb::post) return false;
  const std::optional<std::string> path = pathOf(request);
  return path && *path == kScansPath;
}

bool isScanRoute(const Request& request) {
  const std::optional<std::string> path = pathOf(request);
  return path && path->rfind(std::string(kScansPath) + "/", 0) == 0;
}

void stageScan(server::PlanningService& service, UploadRequest request, std::function<void(StringResponse)> done) {
  boost::asio::post(service.importPool(), [&service, request = std::move(request), done = std::move(done)]() mutable {
    const ReplyTo to = replyTo(request.head);
    StringResponse reply;
    try {
      const std::vector<FormPartSpan> parts = formParts(request);
      std::vector<server::UploadedFile> files;
      for (const FormPartSpan& p : parts) {
        if (p.fileName.empty() && p.size == 0) continue;  // an empty file input
        if (p.name != "dicom" && p.name != "dicom_zip")
          throw server::PatientImportError("bad_field", p.name,
                                           p.name + ": no such field (dicom: the scan's files, or dicom_zip)");
        files.push_back({p.name, p.fileName, formFile(request, p)});
      }
      const server::StagedScan staged = service.scans().stage(files);
      reply = jsonResponse(http::status::created,
                           {{"token", staged.token},
                            {"series", seriesJson(staged.series)},
                            {"read", staged.read},
                            {"expires_after_s", service.scans().expiry().count()}},
                           to);
    } catch (const server::PatientImportError& e) {
      reply = importErrorReply(e, kScansPath, to);
    } catch (const std::exception& e) {
      reply = importFailureReply(e, kScansPath, to);
    }
    request.body.reset();  // the body file and the slot go before the client hears
    done(std::move(reply));
  });
}

// GET /api/scans/<token>: the stage of the import under way, answered here and at once (not
// behind the import on the import pool), so that the page can show it while it waits.
bool scanStatus(server::PlanningService& service, const Request& request, std::function<void(StringResponse)>& done) {
  if (request.method() != http::verb::get) return false;
  const ReplyTo to = replyTo(request);
  const std::string path = pathOf(request).value_or("");
  const std::string token = path.substr(std::min(path.size(), std::string(kScansPath).size() + 1));
  const std::optional<server::ScanStore::Status> status =
      isHexToken(token) ? service.scans().status(token) : std::nullopt;
  if (!status)
    done(jsonError(http::status::not_found, "unknown_scan", "no staged scan with this token", path, to));
  else
    done(jsonResponse(http::status::ok, {{"stage", status->stage}, {"seconds", status->seconds}}, to));
  return true;
}

void scanRoute(server::PlanningService& service, Request request, std::function<void(StringResponse)> done) {
  if (scanStatus(service, request, done)) return;
  boost::asio::post(service.importPool(), [&service, request = std::move(request), done = std::move(done)] {
    const ReplyTo to = replyTo(request);
    const std::string path = pathOf(request).value_or("");
    try {
      std::string rest = path.substr(std::string(kScansPath).size() + 1);
      const std::size_t slash = rest.find('/');
      const std::string token = rest.substr(0, slash);
      const std::string action = slash == std::string::npos ? "" : rest.substr(slash + 1);
      if (!isHexToken(token))
        throw server::PatientImportError("unknown_scan", "token", "no staged scan with this token");
      const http::verb method = request.method();
      if (action == "preview" && method == http::verb::post) {
        const server::ScanPreview preview = service.scans().preview(token, choiceFromJson(jsonBody(request)));
        return done(jsonResponse(http::status::ok, previewJson(preview), to));
      }
      if (action == "import" && method == http::verb::post) {
        const server::ImportedPatient imported = service.scans().importScan(token, uploadFromJson(jsonBody(request)));
        return done(jsonResponse(http::status::created, importedJson(imported), to));
      }
      if (action.empty() && method == http::verb::delete_) {
        if (!service.scans().discard(token))
          throw server::PatientImportError("unknown_scan", "token", "no staged scan with this token (or it is busy)");
        return done(jsonResponse(http::status::ok, {{"discarded", token}}, to));
      }
      if (action == "preview" || action == "import" || action.empty())
        return done(jsonError(http::status::method_not_allowed, "method_not_allowed",
                              std::string(action.empty() ? "GET or DELETE" : "POST") + " only", path, to));
      done(jsonError(http::status::not_found, "not_found", "no such route", path, to));
    } catch (const server::PatientImportError& e) {
      done(importErrorReply(e, path, to));
    } catch (const std::exception& e) {
      done(importFailureReply(e, path, to));
    }
  });
}

}  // namespace orthosim::net
