#pragma once
// Answers one HTTP request: /api/* from ApiRoutes, anything else from the web folder. Immutable
// after construction, so every network thread shares one.
#include "net/ApiRoutes.hpp"
#include "net/HttpMessages.hpp"
#include "net/WebRoot.hpp"

namespace orthosim::net {

class Router {
 public:
  Router(WebRoot web, ApiRoutes api);

  Response handle(const Request& request) const;

 private:
  WebRoot web_;
  ApiRoutes api_;
};

}  // namespace orthosim::net
