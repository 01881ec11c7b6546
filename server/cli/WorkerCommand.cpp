// `orthosim worker`: fine, band and cohort jobs from Redis Streams on this machine (jobs/RedisWorker.hpp).
#include <pthread.h>

#include <csignal>
#include <iostream>
#include <thread>

#include "cli/Commands.hpp"
#include "jobs/RedisWorker.hpp"
#include "session/DataFolderLeftovers.hpp"
#include "session/DataFolderLock.hpp"

namespace orthosim::cli {
namespace fs = std::filesystem;

int runWorker(const WorkerOptions& options) {
  try {
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
    worker.concurrency = options.concurrency;
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
    std::cout << "worker ready: " << options.concurrency << " on " << worker.redis.text << ", data in "
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

}  // namespace orthosim::cli
