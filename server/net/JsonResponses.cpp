#include "net/JsonResponses.hpp"

#include "util/ClientText.hpp"

namespace orthosim::net {

void setCommonHeaders(http::response_header<>& header) {
  header.set(http::field::server, "orthosim/" ORTHOSIM_VERSION);
  header.set("X-Content-Type-Options", "nosniff");  // browsers must trust our Content-Type
}

StringResponse jsonResponse(http::status status, const nlohmann::json& body, const ReplyTo& to) {
  StringResponse response{status, to.version};
  setCommonHeaders(response.base());
  response.set(http::field::content_type, "application/json");
  response.set(http::field::cache_control, "no-store");  // API answers describe the live state
  response.keep_alive(to.keepAlive);
  // Paths echoed in errors may hold any bytes: replace invalid UTF-8 instead of throwing.
  response.body() = body.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
  response.prepare_payload();
  if (to.headOnly) response.body().clear();  // Content-Length still gives the GET size
  return response;
}

StringResponse jsonError(http::status status, std::string_view code, const std::string& message, std::string_view path,
                         const ReplyTo& to) {
  return jsonResponse(status, {{"error", code}, {"message", server::withoutServerPaths(message)}, {"path", path}}, to);
}

}  // namespace orthosim::net
