#pragma once
// What every connection needs, shared by the listener and its sessions: the router, the planning
// service WebSocket sessions talk to, and the limits.
#include <memory>

#include "net/HttpLimits.hpp"
#include "net/Router.hpp"
#include "net/WebSocketSession.hpp"

namespace orthosim::net {

struct ConnectionContext {
  std::shared_ptr<const Router> router;
  server::PlanningService* planning = nullptr;
  HttpLimits limits;
  WebSocketLimits webSocket;
};

}  // namespace orthosim::net
