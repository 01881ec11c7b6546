// `orthosim serve`: the planning server (HTTP, the /ws WebSocket API, fine jobs).
#include <csignal>
#include <cstdlib>
#include <iostream>

#include "cli/Commands.hpp"
#include "jobs/ReplicaClaim.hpp"
#include "net/Server.hpp"
#include "net/TokenFile.hpp"

namespace orthosim::cli {
namespace fs = std::filesystem;
namespace {

fs::path defaultDataDir() {
  if (const char* d = std::getenv("ORTHOSIM_DATA"); d && *d) return d;
  if (const char* x = std::getenv("XDG_DATA_HOME"); x && *x) return fs::path(x) / "orthosim";
  if (const char* h = std::getenv("HOME"); h && *h) return fs::path(h) / ".local" / "share" / "orthosim";
  return fs::current_path() / "orthosim-data";
}

net::ServerOptions serverOptions(const ServeOptions& options) {
  net::ServerOptions server;
  server.host = options.host;
  server.port = static_cast<unsigned short>(options.port);
  server.webDir = options.webDir;
  server.access.token = options.token;
  if (server.access.token.empty())
    if (const char* t = std::getenv("ORTHOSIM_TOKEN")) server.access.token = t;
  if (server.access.token.empty() && !options.tokenFile.empty()) {
    server.access.token = net::loadOrCreateToken(options.tokenFile);
    std::cerr << "orthosim serve: access token in " << options.tokenFile << "\n";
  }
  server.insecure = options.insecure;
  server.access.allowedOrigins = options.allowedOrigins;
  server.access.allowedHosts = options.allowedHosts;
  server.planning.dataDir = dataDirOrDefault(options.dataDir);
  fs::create_directories(server.planning.dataDir);
  server.planning.cases = caseCatalog(options.builtinDir, options.casesDir, "serve");
  server.limits.uploadBytes = static_cast<std::size_t>(options.maxUploadMb) * 1024 * 1024;
  server.limits.maxUploads = options.maxUploads;
  server.planning.scanExpiry = std::chrono::seconds(options.scanExpirySeconds);
  server.planning.maxStagedScans = options.maxStagedScans;
  server.planning.fineWorkers = options.fineWorkers;
  server.planning.redisUrl = options.redis;
  server.planning.replica =
      options.replica.empty() ? server::defaultReplicaName(options.port) : server::checkedReplicaName(options.replica);
  server.planning.orphanGrace = std::chrono::seconds(options.orphanGraceSeconds);
  server.planning.maxSessions = options.maxSessions;
  server.webSocket.unopenedTimeout = std::chrono::seconds(options.unopenedTimeoutSeconds);
  server.planning.previewIterations = options.previewIterations;
  server.planning.previewTime = std::chrono::milliseconds(static_cast<long long>(options.previewSeconds * 1000));
  if (options.warmUp) server.warmUpCase = "phantom-0";
  return server;
}

}  // namespace

std::vector<server::CaseEntry> caseCatalog(const std::string& builtinDir, const std::string& casesDir,
                                           const std::string& command) {
  std::vector<server::CaseEntry> cases = server::builtInCases(builtinDir);
  if (!builtinDir.empty() && cases.size() == server::builtInCases({}).size())
    std::cerr << "orthosim " << command << ": no ArtiSynth face in " << builtinDir
              << " (--builtin-cases): phantom only\n";
  if (!casesDir.empty()) {
    std::vector<std::string> skipped;
    for (server::CaseEntry& c : server::folderCases(casesDir, &skipped)) {
      if (c.id.rfind("phantom-", 0) == 0 || c.id == server::kArtisynthFaceId) {
        std::cerr << "orthosim " << command << ": case folder " << c.id << " skipped: the name is a built-in case's\n";
        continue;
      }
      cases.push_back(std::move(c));
    }
    for (const std::string& s : skipped) std::cerr << "orthosim " << command << ": skipped " << s << "\n";
  }
  return cases;
}

fs::path dataDirOrDefault(const std::string& dataDir) {
  return fs::absolute(dataDir.empty() ? defaultDataDir() : fs::path(dataDir));
}

int runServe(const ServeOptions& options) {
  try {
    const net::ServerOptions server = serverOptions(options);
    net::Server running(server);
    // Tests and scripts read the port from this line (port 0 picks a free one): keep its form.
    std::cout << "listening on http://" << running.host() << ":" << running.port() << std::endl;
    std::cerr << "orthosim serve: web page from " << server.webDir.string() << ", data in "
              << server.planning.dataDir.string() << (server.access.token.empty() ? "" : ", token required") << "\n";
    const int signal = running.runUntilSignal();
    std::cerr << "orthosim serve: stopped by " << (signal == SIGINT ? "SIGINT" : "SIGTERM") << "\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "orthosim serve: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace orthosim::cli
