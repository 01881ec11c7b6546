#pragma once
// POST /api/patients: the page's "New patient" form (multipart/form-data: the fields id, name,
// units, cuts and the files skin, skull, mandible, cavity..., texture, landmarks, or a CT scan's
// dicom files or dicom_zip with series, thresholds and seeds) imported as a new case
// (server/cases/PatientImport). With net/ScanRoutes, the only HTTP routes that change state: they
// take files, which the WebSocket's message limit would not. Its body may be as large as
// HttpLimits::uploadBytes; Host, token and Origin are checked on the headers, before any of the
// body is read.
#include <functional>
#include <vector>

#include "net/HttpMessages.hpp"
#include "net/MultipartForm.hpp"
#include "net/UploadBody.hpp"
#include "session/PlanningService.hpp"

namespace orthosim::net {

inline constexpr const char* kPatientsPath = "/api/patients";

// Whether the request (its headers are enough) is an upload to kPatientsPath.
bool isPatientUpload(const Request& request);

// The upload a form describes (its parts located in the request's body file). Throws
// server::PatientImportError naming the field at fault.
server::PatientUpload patientUploadFromForm(const UploadRequest& request, const std::vector<FormPartSpan>& parts);

// Refuses (server::PatientImportError bad_field, field "cuts") a template the engine does not know,
// naming it and the known ones.
void checkCutTemplates(const std::vector<std::string>& cuts);

// Parses the form, imports on the service's import pool and calls `done` there with the reply:
// 201 {"case": {...as in /api/cases}, "scale", "frame", "warnings", "built", "scan", "suggested"}, or
// 400 / 409 / 415 with {"error", "message", "path", "field", "series" (several_series)}; 500 with
// field "" when the server fails.
// The request's body file is removed when the import ends, however it ends.
void importPatient(server::PlanningService& service, UploadRequest request, std::function<void(StringResponse)> done);

}  // namespace orthosim::net
