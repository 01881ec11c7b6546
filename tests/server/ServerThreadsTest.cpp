// The server's threads stay within its budget (docs/threads.md): previews of several sessions and a
// fine job run on the pools the budget sizes, and the libraries they call start no teams or pools
// of their own.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "ServerProcess.hpp"
#include "WsTestClient.hpp"

namespace orthosim {
namespace {
using nlohmann::json;
using namespace std::chrono_literals;

int threadsOf(pid_t pid) {
  std::error_code error;
  int n = 0;
  for (std::filesystem::directory_iterator it("/proc/" + std::to_string(pid) + "/task", error), end;
       !error && it != end; it.increment(error))
    ++n;
  return n;
}

// The most threads the process had while it lived, sampled every 5 ms.
class ThreadSampler {
 public:
  explicit ThreadSampler(pid_t pid)
      : thread_([this, pid] {
          while (!stop_) {
            most_ = std::max(most_.load(), threadsOf(pid));
            std::this_thread::sleep_for(5ms);
          }
        }) {}
  ~ThreadSampler() { stopNow(); }
  int most() {
    stopNow();
    return most_;
  }

 private:
  void stopNow() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
  }
  std::atomic<bool> stop_{false};
  std::atomic<int> most_{0};
  std::thread thread_;
};

}  // namespace

TEST(ServerThreads, StayWithinTheBudgetDuringPreviewsOfSeveralSessionsAndAFineJob) {
  constexpr int budget = 2, fineWorkers = 1;
  test::ServerProcess server({"--threads", std::to_string(budget), "--fine-workers", std::to_string(fineWorkers)});
  // What the budget allows (docs/threads.md): two network threads (the first is the main thread),
  // the previews and the render threads (one each per thread of the budget), llvmpipe's
  // rasterizers and compute pool (as many) and Mesa's shader-cache queue, imports, one thread each
  // for openings, face fits, exports and requests, the fine workers.
  const int network = 2, render = budget, llvmpipe = 2 * budget + 1, imports = 1, background = 4;
  const int allowed = network + budget + render + llvmpipe + imports + background + fineWorkers;
  ThreadSampler sampler(server.pid());
  std::vector<std::unique_ptr<test::WsTestClient>> sessions;
  for (int i = 0; i < 3; ++i) {
    auto& ws = *sessions.emplace_back(std::make_unique<test::WsTestClient>(server.port()));
    ws.request({{"type", "open"}, {"case", "phantom-0"}});
    ws.waitFor("opened", 120s);
  }
  sessions[0]->request({{"type", "set_poses"}, {"poses", {{"maxilla", {{"anterior_mm", 3}}}}}, {"preview", false}});
  const long long job = sessions[0]->request({{"type", "confirm"}})["job"];
  sessions[0]->waitFor("job_progress", 60s);
  for (int step = 1; step <= 4; ++step)
    for (auto& ws : sessions) {
      const double mm = 1.5 * step;
      ws->request({{"type", "set_poses"}, {"poses", {{"mandible", {{"anterior_mm", mm}}}}}});
      ws->waitFor(
          [mm](const json& m) {
            return m.value("type", "") == "preview" && m["poses"]["mandible"].value("anterior_mm", 0.0) == mm;
          },
          60s);
    }
  const int most = sampler.most();
  EXPECT_LE(most, allowed) << "threads beyond the budget's pools: a library started a team or pool of its own";
  EXPECT_GE(most, network + budget) << "the sampler saw the server's pools";
  sessions[0]->request({{"type", "cancel"}, {"job", job}});
}

}  // namespace orthosim
