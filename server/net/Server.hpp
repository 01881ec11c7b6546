#pragma once
// The planning server: one io_context served by a small pool of network threads, the HTTP
// listener, the planning service, and SIGINT/SIGTERM handling. Network threads only parse, route
// and write; solves run on the planning service's threads, never here.
#include <filesystem>
#include <memory>
#include <string>

#include "net/AccessPolicy.hpp"
#include "net/HttpLimits.hpp"
#include "net/WebSocketSession.hpp"
#include "session/PlanningService.hpp"

namespace orthosim::net {

struct ServerOptions {
  std::string host = "127.0.0.1";  // loopback only unless asked otherwise
  unsigned short port = 8080;      // 0: any free port (see Server::port)
  std::filesystem::path webDir;    // the browser page; nothing outside it is served
  int networkThreads = 2;
  HttpLimits limits;
  WebSocketLimits webSocket;
  AccessOptions access;              // token, allowed origins and hosts
  bool insecure = false;             // serve off the loopback without a token (the operator typed --insecure)
  server::PlanningOptions planning;  // data folder, cases, workers
  std::string warmUpCase;            // built in the background at start (empty: none)
};

class Server {
 public:
  // Binds the listening socket and installs the signal handlers, so that a SIGTERM that arrives
  // from here on stops the server cleanly. Throws std::runtime_error (bad host, port taken, no
  // web folder, a bind off the loopback without a token: net/BindRule.hpp) with a message naming
  // the problem.
  explicit Server(const ServerOptions& options);
  ~Server();

  std::string host() const;  // the bound address, bracketed if IPv6
  unsigned short port() const;

  // Serves until SIGINT or SIGTERM; returns the signal number once every network thread has
  // stopped. Connections still open are closed when the Server is destroyed.
  int runUntilSignal();
  // Makes runUntilSignal return (0) from another thread, as a signal would.
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace orthosim::net
