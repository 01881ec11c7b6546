#include "net/ApiRoutes.hpp"

#include "net/JsonResponses.hpp"

namespace orthosim::net {
namespace {

constexpr std::string_view kExports = "/api/exports/";

StringResponse download(const server::ExportedFile& file, const ReplyTo& to) {
  StringResponse response{http::status::ok, to.version};
  setCommonHeaders(response.base());
  response.set(http::field::content_type, file.contentType);
  response.set(http::field::content_disposition, "attachment; filename=\"" + file.fileName + "\"");
  response.set(http::field::cache_control, "no-store");
  response.keep_alive(to.keepAlive);
  response.body() = file.bytes;
  response.prepare_payload();
  if (to.headOnly) response.body().clear();
  return response;
}

}  // namespace

ApiRoutes::ApiRoutes(server::PlanningService& service) : service_(service) {}

std::optional<Response> ApiRoutes::get(std::string_view path, const ReplyTo& to) const {
  if (path == "/api/health") return jsonResponse(http::status::ok, service_.health(ORTHOSIM_VERSION), to);
  if (path == "/api/cases") return jsonResponse(http::status::ok, server::casesJson(service_.cases().catalog()), to);
  if (path.rfind(kExports, 0) == 0) {
    const std::string id(path.substr(kExports.size()));
    if (std::optional<server::ExportedFile> file = service_.exports().find(id)) return download(*file, to);
    return jsonError(http::status::not_found, "not_found", "no export '" + id + "' (exports are kept for a while only)",
                     path, to);
  }
  return std::nullopt;
}

}  // namespace orthosim::net
