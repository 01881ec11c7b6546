#pragma once
// The page's import of a CT or CBCT scan, in steps, so that the files are sent once while the
// surgeon tries thresholds and seeds (docs/protocol.md):
//   POST   /api/scans                   multipart: dicom (many files) or dicom_zip -> 201 {token, series, ...}
//   POST   /api/scans/<token>/preview   JSON {series, skin_threshold, bone_threshold, mandible_seed, skull_seed}
//                                       -> 200 {thresholds and seeds used, notes, images}
//   POST   /api/scans/<token>/import    JSON {id, name, cuts, oral_cavity, and the preview's fields}
//                                       -> 201 as POST /api/patients
//   DELETE /api/scans/<token>           -> 200 {discarded}
// The staging upload has the upload's body limit; the others the ordinary one. Every route is
// checked for Host, token and Origin like the upload, and its work runs on the import pool.
#include <functional>
#include <nlohmann/json.hpp>
#include <vector>

#include "net/HttpMessages.hpp"
#include "net/MultipartForm.hpp"
#include "net/UploadBody.hpp"
#include "session/PlanningService.hpp"
#include "volume/DicomSeries.hpp"

namespace orthosim::net {

inline constexpr const char* kScansPath = "/api/scans";

// POST /api/scans: an upload (the headers are enough).
bool isScanUpload(const Request& request);
// Any request to /api/scans/<...>.
bool isScanRoute(const Request& request);

// Stages the upload's scan (ScanStore::stage) and calls `done` on the import pool.
void stageScan(server::PlanningService& service, UploadRequest request, std::function<void(StringResponse)> done);
// Answers a request to /api/scans/<token>/... on the import pool.
void scanRoute(server::PlanningService& service, Request request, std::function<void(StringResponse)> done);

// [{uid, description, modality, files, rows, columns}] for the page's choice of a series.
nlohmann::json seriesJson(const std::vector<DicomSeriesInfo>& series);
// The reply to a refused upload or scan: {error, message, path, field, series?}, its status by the
// code (404 unknown_scan, 409 case_exists, 503 too_many_scans, else 400). `field` is the form field
// at fault, "body" for the form as a whole, "" when no field is at fault.
StringResponse importErrorReply(const server::PatientImportError& e, const std::string& path, const ReplyTo& to);
// The reply to an upload whose import failed on the server (not the client's fault): 500
// import_failed, the reason logged rather than sent (it may name the server's folders or a
// library's internals).
StringResponse importFailureReply(const std::exception& e, const std::string& path, const ReplyTo& to);
// The parts of a multipart/form-data upload (a patient's or a scan's), located in its body file.
// Throws PatientImportError: bad_form (field "body") for a malformed form, bad_field for a field
// name that is not UTF-8, bad_file for such a file name.
std::vector<FormPartSpan> formParts(const UploadRequest& request);
// A plain field's text: at most 64 KiB of UTF-8, else PatientImportError bad_field naming it.
std::string formText(const UploadRequest& request, const FormPartSpan& part);
// A file part's bytes, in the body file.
server::FileSlice formFile(const UploadRequest& request, const FormPartSpan& part);
// The body of a created case: {case, scale, frame, warnings, built, scan, suggested}.
nlohmann::json importedJson(const server::ImportedPatient& imported);

}  // namespace orthosim::net
