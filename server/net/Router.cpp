#include "net/Router.hpp"

#include "net/JsonResponses.hpp"
#include "net/RequestTarget.hpp"
#include "net/StaticFiles.hpp"

namespace orthosim::net {
namespace {

bool isApiPath(std::string_view path) { return path == "/api" || path.rfind("/api/", 0) == 0; }

StringResponse methodNotAllowed(const Request& request, std::string_view path, const ReplyTo& to) {
  StringResponse response = jsonError(http::status::method_not_allowed, "method_not_allowed",
                                      std::string(request.method_string()) + " is not allowed here; use GET", path, to);
  response.set(http::field::allow, "GET, HEAD");
  return response;
}

}  // namespace

Router::Router(WebRoot web, ApiRoutes api) : web_(std::move(web)), api_(std::move(api)) {}

Response Router::handle(const Request& request) const {
  const ReplyTo to = replyTo(request);
  const std::string_view rawTarget(request.target().data(), request.target().size());
  const std::optional<RequestTarget> target = parseRequestTarget(rawTarget);
  if (!target)
    return jsonError(http::status::bad_request, "bad_target", "malformed request target", rawTarget, to);

  // Both the API and the page are read-only over HTTP: state changes go over the WebSocket.
  const bool readOnly = request.method() == http::verb::get || request.method() == http::verb::head;
  if (isApiPath(target->path)) {
    std::optional<nlohmann::json> body = api_.get(target->path);
    if (!body) return jsonError(http::status::not_found, "not_found", "no API route " + target->path, target->path, to);
    if (!readOnly) return methodNotAllowed(request, target->path, to);
    return jsonResponse(http::status::ok, *body, to);
  }
  if (!readOnly) return methodNotAllowed(request, target->path, to);
  return serveStaticFile(web_, target->path, to);
}

}  // namespace orthosim::net
