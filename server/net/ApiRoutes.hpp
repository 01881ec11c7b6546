#pragma once
// The HTTP API under /api: facts about the server (health, cases) and downloads of exported
// files. Everything that changes state goes over the WebSocket (/ws).
#include <optional>
#include <string_view>

#include "net/HttpMessages.hpp"
#include "session/PlanningService.hpp"

namespace orthosim::net {

class ApiRoutes {
 public:
  explicit ApiRoutes(server::PlanningService& service);

  // The reply to GET `path`, or nullopt when no API route has that path.
  std::optional<Response> get(std::string_view path, const ReplyTo& to) const;

 private:
  server::PlanningService& service_;
};

}  // namespace orthosim::net
