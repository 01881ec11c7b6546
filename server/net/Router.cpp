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

StringResponse refusal(const Refusal& r, std::string_view path, const ReplyTo& to) {
  StringResponse response = jsonError(r.status, r.code, r.message, path, to);
  if (r.status == http::status::unauthorized) response.set(http::field::www_authenticate, "Bearer");
  return response;
}

}  // namespace

Router::Router(WebRoot web, ApiRoutes api, AccessPolicy policy)
    : web_(std::move(web)), api_(std::move(api)), policy_(std::move(policy)) {}

Response Router::handle(const Request& request) const {
  const ReplyTo to = replyTo(request);
  const std::string_view rawTarget(request.target().data(), request.target().size());
  const std::optional<RequestTarget> target = parseRequestTarget(rawTarget);
  if (!target) return jsonError(http::status::bad_request, "bad_target", "malformed request target", rawTarget, to);
  if (std::optional<Refusal> r = policy_.checkHost(request)) return refusal(*r, target->path, to);

  // Both the API and the page are read-only over HTTP: state changes go over the WebSocket.
  const bool readOnly = request.method() == http::verb::get || request.method() == http::verb::head;
  if (isApiPath(target->path)) {
    if (std::optional<Refusal> r = policy_.checkToken(request, *target)) return refusal(*r, target->path, to);
    std::optional<Response> reply = api_.get(target->path, to);
    if (!reply)
      return jsonError(http::status::not_found, "not_found", "no API route " + target->path, target->path, to);
    if (!readOnly) return methodNotAllowed(request, target->path, to);
    return std::move(*reply);
  }
  if (target->path == "/ws")
    return jsonError(http::status::upgrade_required, "upgrade_required",
                     "/ws is the WebSocket API: open it as a WebSocket", target->path, to);
  if (!readOnly) return methodNotAllowed(request, target->path, to);
  return serveStaticFile(web_, target->path, to);
}

std::optional<StringResponse> Router::refuseUpload(const Request& request) const {
  const ReplyTo to{request.version(), false, false};
  const std::optional<RequestTarget> target =
      parseRequestTarget(std::string_view(request.target().data(), request.target().size()));
  if (!target) return jsonError(http::status::bad_request, "bad_target", "malformed request target", "", to);
  // A page of another site may post a form here without asking (no CORS preflight): Origin too.
  for (auto check : {&AccessPolicy::checkHost, &AccessPolicy::checkOrigin})
    if (std::optional<Refusal> r = (policy_.*check)(request)) return refusal(*r, target->path, to);
  if (std::optional<Refusal> r = policy_.checkToken(request, *target)) return refusal(*r, target->path, to);
  return std::nullopt;
}

std::optional<StringResponse> Router::refuseUpgrade(const Request& request) const {
  const ReplyTo to{request.version(), false, false};
  const std::string_view rawTarget(request.target().data(), request.target().size());
  const std::optional<RequestTarget> target = parseRequestTarget(rawTarget);
  if (!target) return jsonError(http::status::bad_request, "bad_target", "malformed request target", rawTarget, to);
  if (target->path != "/ws")
    return jsonError(http::status::not_found, "not_found", "WebSocket upgrades are served on /ws only", target->path,
                     to);
  for (auto check : {&AccessPolicy::checkHost, &AccessPolicy::checkOrigin})
    if (std::optional<Refusal> r = (policy_.*check)(request)) return refusal(*r, target->path, to);
  if (std::optional<Refusal> r = policy_.checkToken(request, *target)) return refusal(*r, target->path, to);
  return std::nullopt;
}

}  // namespace orthosim::net
