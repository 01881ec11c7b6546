#pragma once
// A predicted skin as a file to download (the "export" message, docs/protocol.md): STL, OBJ or
// PLY bytes with the file's name and content type, for the service's ExportStore to serve.
#include <Eigen/Core>
#include <string>

#include "scene/CaseModel.hpp"

namespace orthosim::server {

// The format in lower case; throws ProtocolError bad_value for anything but stl, obj, ply.
std::string skinExportFormat(std::string format);

struct SkinExport {
  std::string fileName;  // <case id>-<result>.<format>, e.g. "phantom-0-preview.stl"
  std::string contentType;
  std::string bytes;
};

// A surface as <fileStem>.<format>.
SkinExport surfaceExportFile(const SurfaceMesh& surface, const std::string& fileStem, const std::string& format);

// The model's skin at nodes `x`; `result` ("preview" or "fine") names the file.
SkinExport skinExportFile(const CaseModel& model, const Eigen::Matrix3Xd& x, const std::string& caseId,
                          const std::string& result, const std::string& format);

}  // namespace orthosim::server
