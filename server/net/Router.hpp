#pragma once
// Answers one HTTP request: /api/* from ApiRoutes, anything else from the web folder, after the
// access checks (Host, token). Also decides whether a WebSocket upgrade to /ws may proceed.
// Immutable after construction, so every network thread shares one.
#include <optional>

#include "net/AccessPolicy.hpp"
#include "net/ApiRoutes.hpp"
#include "net/HttpMessages.hpp"
#include "net/WebRoot.hpp"

namespace orthosim::net {

class Router {
 public:
  Router(WebRoot web, ApiRoutes api, AccessPolicy policy);

  Response handle(const Request& request) const;
  // nullopt when the upgrade may proceed (path /ws, Host, token and Origin accepted); otherwise
  // the reply that refuses it.
  std::optional<StringResponse> refuseUpgrade(const Request& request) const;
  // The same for an upload (isPatientUpload), on its headers, before its body is read.
  std::optional<StringResponse> refuseUpload(const Request& request) const;

 private:
  WebRoot web_;
  ApiRoutes api_;
  AccessPolicy policy_;
};

}  // namespace orthosim::net
