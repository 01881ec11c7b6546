// `orthosim serve`: the planning server (HTTP, the /ws WebSocket API, fine jobs).
#include <csignal>
#include <cstdlib>
#include <iostream>
#include <memory>

#include "cli/CommandLine.hpp"
#include "cli/CommandRun.hpp"
#include "cli/Commands.hpp"
#include "cli/SharedOptions.hpp"
#include "jobs/ReplicaClaim.hpp"
#include "net/Server.hpp"
#include "net/TokenFile.hpp"
#include "system/ThreadBudget.hpp"

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
  server.planning.previewThreads = threadBudget();
  server.planning.renderThreads = threadBudget();
  server.planning.fineWorkers = options.fineWorkers;
  server.planning.redisUrl = options.redis;
  server.planning.replica =
      options.replica.empty() ? server::defaultReplicaName(options.port) : server::checkedReplicaName(options.replica);
  server.planning.orphanGrace = std::chrono::seconds(options.orphanGraceSeconds);
  server.planning.maxSessions = options.maxSessions;
  server.planning.modelMemoryBytes = static_cast<std::size_t>(options.modelMemoryMiB) << 20;
  server.webSocket.unopenedTimeout = std::chrono::seconds(options.unopenedTimeoutSeconds);
  server.planning.previewIterations = options.previewIterations;
  server.planning.previewTime = std::chrono::milliseconds(static_cast<long long>(options.previewSeconds * 1000));
  server.planning.faceFitTime = std::chrono::milliseconds(static_cast<long long>(options.faceFitSeconds * 1000));
  server.planning.maxJobsPerSession = options.jobsPerSession;
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
    setThreadBudget(options.threads);
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

namespace {

// Where the server listens, what it serves, and who may reach it.
void addServeAccessOptions(CLI::App& serve, ServeOptions& o) {
  serve.add_option("--host", o.host, "Address to bind (default 127.0.0.1: this machine only)");
  serve.add_option("--port", o.port, "TCP port; 0 picks a free one")->check(CLI::Range(0, 65535));
  serve.add_option("--web", o.webDir, "Folder of the browser page (default: the source tree's web/)");
  addDataOption(serve, o.dataDir,
                "Folder for built cases, the mesh cache and saved plans (default: $ORTHOSIM_DATA, else "
                "~/.local/share/orthosim)");
  serve.add_option("--cases", o.casesDir, "Folder of case folders (DIR/<id>/case.json) to serve besides the phantom");
  serve.add_option("--builtin-cases", o.builtinDir,
                   "Folder of the shipped cases (default: the source tree's cases/; holds the ArtiSynth face)");
  serve.add_option("--token", o.token, "Access token required on /api and /ws (default: $ORTHOSIM_TOKEN)");
  serve.add_option("--token-file", o.tokenFile,
                   "Without --token or $ORTHOSIM_TOKEN: read the token from this file, or write a random one there");
  serve.add_flag("--insecure", o.insecure,
                 "Allow a --host other than the loopback without a token (anyone who reaches the port can plan)");
  serve.add_option("--allow-origin", o.allowedOrigins,
                   "Origin (e.g. http://planning.example:8080) whose pages may open the WebSocket; '*' allows any");
  serve.add_option("--allow-host", o.allowedHosts,
                   "Host name clients may use besides localhost, addresses and this machine's name (\"*\": any)");
}

// How much work the server takes on at once, and for how long.
void addServeLimitOptions(CLI::App& serve, ServeOptions& o) {
  addThreadsOption(serve, o.threads);
  serve.add_option("--fine-workers", o.fineWorkers, "Fine jobs run at once")->check(CLI::Range(1, 16));
  serve.add_option("--max-sessions", o.maxSessions, "Planning sessions open at once")->check(CLI::Range(1, 1024));
  addModelMemoryOption(serve, o.modelMemoryMiB);
  serve
      .add_option("--preview-iterations", o.previewIterations,
                  "Newton iterations one coarse preview may spend (beyond: refused, the last good preview kept)")
      ->check(CLI::Range(1, 10000));
  serve.add_option("--preview-seconds", o.previewSeconds, "Seconds one coarse preview may take")
      ->check(CLI::Range(0.1, 3600.0));
  serve
      .add_option("--face-fit-seconds", o.faceFitSeconds,
                  "Seconds one face fit (plan_from_face) may take; it stops there with the best poses so far")
      ->check(CLI::Range(0.001, 3600.0));
  serve
      .add_option("--jobs-per-session", o.jobsPerSession,
                  "Fine and band jobs one session may have queued or running (beyond: refused until one ends)")
      ->check(CLI::Range(1, 1024));
  serve
      .add_option("--unopened-timeout", o.unopenedTimeoutSeconds,
                  "Seconds a session may stay without opening a case before it is closed")
      ->check(CLI::Range(1, 86400));
  serve.add_flag("!--no-warm-up", o.warmUp, "Do not build the phantom's coarse model at start");
  serve.add_option("--max-upload-mb", o.maxUploadMb, "Largest patient upload (POST /api/patients), MiB")
      ->check(CLI::Range(1, 4096));
  serve
      .add_option("--max-uploads", o.maxUploads,
                  "Uploads (POST /api/patients, /api/scans) received or imported at once; more get 503")
      ->check(CLI::Range(1, 256));
  serve
      .add_option("--scan-expiry", o.scanExpirySeconds,
                  "Seconds a scan staged for import (POST /api/scans) is kept unused before it is removed")
      ->check(CLI::Range(1, 86400));
  serve.add_option("--max-staged-scans", o.maxStagedScans, "Scans staged for import at once")->check(CLI::Range(1, 64));
}

// Fine jobs on `orthosim worker` processes through Redis.
void addServeRedisOptions(CLI::App& serve, ServeOptions& o) {
  serve.add_option("--redis", o.redis,
                   "redis://HOST:PORT: fine jobs go to `orthosim worker` processes through Redis Streams "
                   "(default: run them in this process)");
  serve.add_option("--replica", o.replica,
                   "With --redis: this server's name there, the same after a restart so that its queued jobs "
                   "are found again; one per running server (default: HOST-PORT)");
  serve
      .add_option("--orphan-grace", o.orphanGraceSeconds,
                  "With --redis: seconds a fine job whose session is gone waits for a session to resume it")
      ->check(CLI::Range(1, 86400));
}

}  // namespace

void addServeCommand(CLI::App& parent) {
  auto options = std::make_shared<ServeOptions>();
  options->webDir = ORTHOSIM_WEB_DIR;
  options->builtinDir = ORTHOSIM_CASES_DIR;
  auto* serve = parent.add_subcommand("serve", "Serve the planning API and the browser page over HTTP");
  addServeAccessOptions(*serve, *options);
  addServeLimitOptions(*serve, *options);
  addServeRedisOptions(*serve, *options);
  runWhenChosen(*serve, [options] { return runServe(*options); });
}

}  // namespace orthosim::cli
