// `orthosim serve`: the planning server (HTTP for now; the WebSocket API follows, issue 5).
#include <csignal>
#include <iostream>

#include "cli/Commands.hpp"
#include "net/Server.hpp"

namespace orthosim::cli {

int runServe(const ServeOptions& options) {
  net::ServerOptions server;
  server.host = options.host;
  server.port = options.port;
  server.webDir = options.webDir;
  try {
    net::Server running(server);
    // Tests and scripts read the port from this line (port 0 picks a free one): keep its form.
    std::cout << "listening on http://" << running.host() << ":" << running.port() << std::endl;
    std::cerr << "orthosim serve: web page from " << server.webDir.string() << "\n";
    const int signal = running.runUntilSignal();
    std::cerr << "orthosim serve: stopped by " << (signal == SIGINT ? "SIGINT" : "SIGTERM") << "\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "orthosim serve: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace orthosim::cli
