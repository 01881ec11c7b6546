#include "session/SkinExport.hpp"

#include <algorithm>
#include <cctype>

#include "io/SurfaceImport.hpp"
#include "session/ProtocolError.hpp"

namespace orthosim::server {

std::string skinExportFormat(std::string format) {
  std::transform(format.begin(), format.end(), format.begin(), [](unsigned char ch) { return std::tolower(ch); });
  if (format != "stl" && format != "obj" && format != "ply")
    throw ProtocolError("bad_value", "/format: '" + format + "' is not one of stl, obj, ply", "/format");
  return format;
}

SkinExport surfaceExportFile(const SurfaceMesh& surface, const std::string& fileStem, const std::string& format) {
  SkinExport e;
  e.bytes = exportSurfaceBytes(surface, format);
  e.contentType = format == "stl" ? "model/stl" : format == "obj" ? "model/obj" : "application/x-ply";
  e.fileName = fileStem + "." + format;
  return e;
}

SkinExport skinExportFile(const CaseModel& model, const Eigen::Matrix3Xd& x, const std::string& caseId,
                          const std::string& result, const std::string& format) {
  return surfaceExportFile(model.deformedSkin(x), caseId + "-" + result, format);
}

}  // namespace orthosim::server
