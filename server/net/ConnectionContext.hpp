#pragma once
// What every connection needs, shared by the listener and its sessions: the router, the planning
// service WebSocket sessions talk to, the limits and the uploads under way.
#include <memory>

#include "net/HttpLimits.hpp"
#include "net/Router.hpp"
#include "net/UploadSlots.hpp"
#include "net/WebSocketSession.hpp"

namespace orthosim::net {

struct ConnectionContext {
  std::shared_ptr<const Router> router;
  server::PlanningService* planning = nullptr;
  HttpLimits limits;
  std::shared_ptr<UploadSlots> uploads;  // shared by every connection
  WebSocketLimits webSocket;
};

}  // namespace orthosim::net
