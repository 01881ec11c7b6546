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
#include "session/PlanningService.hpp"
#include "volume/DicomSeries.hpp"

namespace orthosim::net {

inline constexpr const char* kScansPath = "/api/scans";

// POST /api/scans: an upload (the headers are enough).
bool isScanUpload(const Request& request);
// Any request to /api/scans/<...>.
bool isScanRoute(const Request& request);

// Stages the upload's scan (ScanStore::stage) and calls `done` on the import pool.
void stageScan(server::PlanningService& service, Request request, std::function<void(StringResponse)> done);
// Answers a request to /api/scans/<token>/... on the import pool.
void scanRoute(server::PlanningService& service, Request request, std::function<void(StringResponse)> done);

// [{uid, description, modality, files, rows, columns}] for the page's choice of a series.
nlohmann::json seriesJson(const std::vector<DicomSeriesInfo>& series);
// The reply to a refused upload or scan: {error, message, path, field?, series?}, its status by the
// code (404 unknown_scan, 409 case_exists, 503 too_many_scans, else 400).
StringResponse importErrorReply(const server::PatientImportError& e, const std::string& path, const ReplyTo& to);
// The parts of a multipart/form-data request (the upload of a patient or a scan). Throws FormError.
std::vector<FormPart> formParts(const Request& request);
// The body of a created case: {case, scale, frame, warnings, built, scan, suggested}.
nlohmann::json importedJson(const server::ImportedPatient& imported);

}  // namespace orthosim::net
