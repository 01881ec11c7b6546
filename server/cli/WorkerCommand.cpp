// `orthosim worker`: fine, band and cohort jobs from Redis Streams on this machine (jobs/RedisWorker.hpp).
#include <pthread.h>

#include <csignal>
#include <iostream>
#include <memory>
#include <thread>

#include "cli/CommandLine.hpp"
#include "cli/CommandRun.hpp"
#include "cli/Commands.hpp"
#include "cli/SharedOptions.hpp"
#include "jobs/RedisWorker.hpp"
#include "session/DataFolderLeftovers.hpp"
#include "session/DataFolderLock.hpp"
#include "system/ThreadBudget.hpp"

namespace orthosim::cli {
namespace fs = std::filesystem;

int runWorker(const WorkerOptions& options) {
  try {
    setThreadBudget(options.threads);
    server::WorkerOptions worker;
    worker.redis = server::parseRedisUrl(options.redis);
    worker.dataDir = dataDirOrDefault(options.dataDir);
    fs::create_directories(worker.dataDir / "jobs");
    // Shared with the servers started with --redis and the other workers; refused while a server
    // without --redis has the folder to itself.
    server::DataFolderLock lock(worker.dataDir, server::DataFolderUse::Shared, "orthosim worker");
    for (const std::string& leftover : server::removeLeftovers(worker.dataDir, lock.alone()))
      std::cerr << "orthosim worker: removed " << leftover << ", left by an interrupted write\n";
    lock.share();
    worker.cases = caseCatalog(options.builtinDir, options.casesDir, "worker");
    worker.concurrency = options.concurrency > 0 ? options.concurrency : threadBudget();
    worker.modelMemoryBytes = static_cast<std::size_t>(options.modelMemoryMiB) << 20;
    worker.visibilityTimeout = std::chrono::milliseconds(static_cast<long long>(options.visibilitySeconds * 1000));
    worker.name = options.name;

    // SIGINT and SIGTERM are taken by this thread alone (sigwait), the job threads never see them.
    sigset_t signals;
    sigemptyset(&signals);
    sigaddset(&signals, SIGINT);
    sigaddset(&signals, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &signals, nullptr);

    server::RedisWorker running(worker);
    std::atomic<bool> stop{false};
    std::thread jobs([&] { running.run(stop); });
    // Tests and scripts wait for this line: keep its form.
    std::cout << "worker ready: " << worker.concurrency << " on " << worker.redis.text << ", data in "
              << worker.dataDir.string() << std::endl;
    int signal = 0;
    sigwait(&signals, &signal);
    std::cerr << "orthosim worker: stopping (" << (signal == SIGINT ? "SIGINT" : "SIGTERM")
              << "); a running job is left for another worker\n";
    stop = true;
    jobs.join();
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "orthosim worker: " << e.what() << "\n";
    return 1;
  }
}

void addWorkerCommand(CLI::App& parent) {
  auto options = std::make_shared<WorkerOptions>();
  WorkerOptions& o = *options;
  o.builtinDir = ORTHOSIM_CASES_DIR;
  auto* worker = parent.add_subcommand(
      "worker",
      "Run fine, band and cohort jobs from Redis Streams (serve --redis, bench cohort --redis) on this machine");
  worker->add_option("--redis", o.redis, "redis://HOST:PORT, the same as the servers'")->required();
  addDataOption(*worker, o.dataDir,
                "The servers' data folder (shared: cases, mesh cache, results; default: $ORTHOSIM_DATA, else "
                "~/.local/share/orthosim)");
  worker->add_option("--cases", o.casesDir, "The servers' --cases folder, if they use one");
  worker->add_option("--builtin-cases", o.builtinDir, "The servers' --builtin-cases folder");
  addThreadsOption(*worker, o.threads);
  worker->add_option("--concurrency", o.concurrency, "Jobs at once (default: one per thread of --threads)")
      ->check(CLI::Range(0, 64));
  addModelMemoryOption(*worker, o.modelMemoryMiB);
  worker
      ->add_option("--visibility-timeout", o.visibilitySeconds,
                   "Seconds after which a job whose worker stopped (died) goes to another worker (default 60)")
      ->check(CLI::Range(0.5, 86400.0));
  worker->add_option("--name", o.name, "Name of this worker in Redis (default: HOST-PID)");
  runWhenChosen(*worker, [options] { return runWorker(*options); });
}

}  // namespace orthosim::cli
