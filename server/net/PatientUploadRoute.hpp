#pragma once
// POST /api/patients: the page's "New patient" form (multipart/form-data: the fields id, name,
// units, cuts and the files skin, skull, mandible, cavity..., texture, landmarks) imported as a new
// case (server/cases/PatientImport). The only HTTP route that changes state: it takes files, which
// the WebSocket's message limit would not. Its body may be as large as HttpLimits::uploadBytes;
// Host, token and Origin are checked on the headers, before any of the body is read.
#include <functional>
#include <vector>

#include "net/HttpMessages.hpp"
#include "net/MultipartForm.hpp"
#include "session/PlanningService.hpp"

namespace orthosim::net {

inline constexpr const char* kPatientsPath = "/api/patients";

// Whether the request (its headers are enough) is an upload to kPatientsPath.
bool isPatientUpload(const Request& request);

// The upload a form describes. Throws server::PatientImportError naming the field at fault.
server::PatientUpload patientUploadFromForm(const std::vector<FormPart>& parts);

// Parses the form, imports on the service's import pool and calls `done` there with the reply:
// 201 {"case": {...as in /api/cases}, "scale", "frame", "warnings"}, or 400 / 409 / 415 with
// {"error", "message", "path", "field"}.
void importPatient(server::PlanningService& service, Request request, std::function<void(StringResponse)> done);

}  // namespace orthosim::net
