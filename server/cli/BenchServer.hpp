#pragma once
// The planning server run inside a bench's own process, on a free loopback port, with the built-in
// cases in `dataDir` and serve's thread budget; stopped and joined when it goes out of scope.
#include <algorithm>
#include <filesystem>
#include <string>
#include <thread>

#include "net/Server.hpp"
#include "system/ThreadBudget.hpp"

namespace orthosim::cli {

class BenchServer {
 public:
  BenchServer(const std::string& webDir, const std::string& dataDir, int minSessions = 0)
      : server_(options(webDir, dataDir, minSessions)), serving_([this] { server_.runUntilSignal(); }) {}
  ~BenchServer() {
    server_.stop();
    serving_.join();
  }
  BenchServer(const BenchServer&) = delete;
  BenchServer& operator=(const BenchServer&) = delete;

  unsigned short port() const { return server_.port(); }

 private:
  static net::ServerOptions options(const std::string& webDir, const std::string& dataDir, int minSessions) {
    net::ServerOptions so;
    so.host = "127.0.0.1";
    so.port = 0;
    so.webDir = webDir;
    so.planning.dataDir = std::filesystem::absolute(dataDir);
    so.planning.maxSessions = std::max(so.planning.maxSessions, minSessions);
    std::filesystem::create_directories(so.planning.dataDir);
    so.planning.cases = server::builtInCases();
    so.planning.previewThreads = threadBudget();
    so.planning.renderThreads = threadBudget();
    return so;
  }

  net::Server server_;
  std::thread serving_;
};

}  // namespace orthosim::cli
