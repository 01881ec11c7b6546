#include "cli/CohortOnRedis.hpp"

#include <fcntl.h>
#include <sched.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "jobs/CohortResultFile.hpp"
#include "jobs/JobMessage.hpp"
#include "jobs/JobStream.hpp"
#include "util/RandomId.hpp"

extern char** environ;

namespace orthosim::cli {
namespace fs = std::filesystem;
using nlohmann::json;
using server::RedisConnection;
using server::RedisValue;

namespace {

struct Pending {
  std::string patient;
  std::string run;  // reference, coarse, fine
};

long long groupField(RedisConnection& redis, const char* field) {
  const RedisValue groups = redis.command({"XINFO", "GROUPS", server::kJobStream});
  for (const RedisValue& g : groups.array) {
    bool ours = false;
    long long value = -1;
    for (size_t k = 0; k + 1 < g.array.size(); k += 2) {
      if (g.array[k].string == "name" && g.array[k + 1].string == server::kWorkerGroup) ours = true;
      if (g.array[k].string == field && g.array[k + 1].kind == RedisValue::Kind::Integer)
        value = g.array[k + 1].integer;
    }
    if (ours) return value;
  }
  return -1;
}

double epochSeconds() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

// The worker's side of a job_done: who ran it and for how long (absent from older workers: zero).
CohortJobTiming jobTiming(const json& reply) {
  CohortJobTiming t;
  t.consumer = reply.value("consumer", std::string());
  t.cores = reply.value("worker_cores", 0);
  t.busySeconds = reply.value("busy_s", 0.0);
  t.caseSeconds = reply.value("case_s", 0.0);
  t.buildSeconds = reply.value("build_s", 0.0);
  t.cpuSeconds = reply.value("cpu_s", 0.0);
  t.startedAt = reply.value("started_at_s", 0.0);
  t.doneAt = epochSeconds();
  return t;
}

// The cores this process may run on, in order.
std::vector<int> allowedCores() {
  cpu_set_t set;
  CPU_ZERO(&set);
  std::vector<int> cores;
  if (::sched_getaffinity(0, sizeof set, &set) == 0)
    for (int c = 0; c < CPU_SETSIZE; ++c)
      if (CPU_ISSET(c, &set)) cores.push_back(c);
  return cores;
}

// Sets this thread's affinity to `core` (a child spawned now inherits it); restores the old one
// at destruction.
class PinnedForSpawn {
 public:
  explicit PinnedForSpawn(int core) {
    CPU_ZERO(&saved_);
    if (core < 0 || ::sched_getaffinity(0, sizeof saved_, &saved_) != 0) return;
    cpu_set_t one;
    CPU_ZERO(&one);
    CPU_SET(core, &one);
    if (::sched_setaffinity(0, sizeof one, &one) != 0)
      throw std::runtime_error("cannot pin a worker to core " + std::to_string(core) + ": " + std::strerror(errno));
    pinned_ = true;
  }
  ~PinnedForSpawn() {
    if (pinned_) ::sched_setaffinity(0, sizeof saved_, &saved_);
  }
  PinnedForSpawn(const PinnedForSpawn&) = delete;
  PinnedForSpawn& operator=(const PinnedForSpawn&) = delete;

 private:
  cpu_set_t saved_;
  bool pinned_ = false;
};

}  // namespace

std::map<std::string, CohortPatientRuns> runCohortOnRedis(const server::RedisAddress& address,
                                                          const std::vector<CohortPatient>& patients,
                                                          const std::map<std::string, CaseSpec>& specs,
                                                          const CohortRedisPlan& plan, const fs::path& dataDir,
                                                          double idleLimit, std::vector<CohortJobTiming>* timings) {
  RedisConnection redis(address);
  server::ensureWorkerGroup(redis);
  const std::string benchId = "bench" + server::randomHexId().substr(0, 12);
  const std::string replies = server::replyStreamName(benchId);
  std::map<std::string, Pending> pending;  // job name -> what it is
  std::map<std::string, CohortPatientRuns> out;
  int n = 0;
  // Patient by patient, each patient's longest run first, so that the last jobs to start are short
  // ones, and jobs that mesh the same tissue (the phantom patients of one variant share their meshes
  // at each resolution) start one after another: a worker then reads the mesh another made instead
  // of waiting for it (or meshing it beside it).
  for (const CohortPatient& p : patients)
    for (const char* run : {"reference", "fine", "coarse"}) {
      server::JobMessage m;
      m.job = benchId + "-" + std::to_string(++n);
      m.kind = server::JobKind::cohort;
      m.caseId = p.id;
      m.caseHash = server::caseContentHash(specs.at(p.id));
      m.resolution = Resolution::Coarse;
      m.replyStream = replies;
      server::CohortJobSpec s;
      const std::string r = run;
      s.config = r == "reference" ? plan.reference : r == "fine" ? plan.fine : plan.coarse;
      s.repeats = r == "reference" ? 1 : plan.repeats;
      s.contact = plan.contact;
      s.fallbackToDefaultTolerances = r == "reference" && plan.referenceFallback;
      m.cohort = s;
      redis.command({"XADD", server::kJobStream, "*", "job", server::encodeJobMessage(m)});
      pending[m.job] = {p.id, r};
      out[p.id];
    }
  std::printf("%d cohort jobs on %s (stream %s), waiting for the workers\n", n, address.text.c_str(),
              server::kJobStream);
  std::fflush(stdout);
  std::string last = "0-0";
  auto lastNews = std::chrono::steady_clock::now();
  while (!pending.empty()) {
    const RedisValue r = redis.command({"XREAD", "COUNT", "100", "BLOCK", "1000", "STREAMS", replies, last});
    if (r.isNil() || r.array.empty()) {
      const double idle = std::chrono::duration<double>(std::chrono::steady_clock::now() - lastNews).count();
      if (idle > idleLimit && groupField(redis, "consumers") <= 0)
        throw std::runtime_error("no worker has read " + std::string(server::kJobStream) + " on " + address.text +
                                 " for " + std::to_string(static_cast<int>(idle)) +
                                 " s: start `orthosim worker --redis " + address.text + " --data " + dataDir.string() +
                                 "` (or use --spawn-workers)");
      continue;
    }
    if (r.array[0].array.size() < 2) continue;
    for (const RedisValue& entry : r.array[0].array[1].array) {
      if (entry.array.size() < 2) continue;  // not an entry: [id, [field, value, ...]]
      last = entry.array[0].string;
      json reply;
      for (size_t k = 0; k + 1 < entry.array[1].array.size(); k += 2)
        if (entry.array[1].array[k].string == "msg")
          reply = json::parse(entry.array[1].array[k + 1].string, nullptr, false);
      if (!reply.is_object() || !reply.contains("job") || !reply["job"].is_string()) continue;
      auto it = pending.find(reply["job"].get<std::string>());
      if (it == pending.end()) continue;
      lastNews = std::chrono::steady_clock::now();
      const std::string type = reply.value("type", "");
      if (type != "job_done" && type != "job_failed" && type != "job_cancelled") continue;
      const Pending job = it->second;
      pending.erase(it);
      CohortPatientRuns& runs = out[job.patient];
      if (type != "job_done") {
        const std::string why = job.run + ": " + reply.value("message", type);
        runs.error += (runs.error.empty() ? "" : "; ") + why;
        std::printf("  %s %s: %s\n", job.patient.c_str(), job.run.c_str(), why.c_str());
        std::fflush(stdout);
        continue;
      }
      try {
        CohortJobTiming timing = jobTiming(reply);
        const fs::path file = dataDir / reply.value("result", std::string());
        server::CohortOutcome o = server::readCohortResult(file, specs.at(job.patient));
        fs::remove(file);
        timing.readSeconds = epochSeconds() - timing.doneAt;
        if (timings) timings->push_back(timing);
        std::printf(
            "  %s %s done on %s: case %.1f s, build %.1f s, solve %.3f s, busy %.1f s, CPU %.1f s (%d pending)\n",
            job.patient.c_str(), job.run.c_str(), timing.consumer.c_str(), timing.caseSeconds, timing.buildSeconds,
            o.run.solveSeconds, timing.busySeconds, timing.cpuSeconds, static_cast<int>(pending.size()));
        std::fflush(stdout);
        if (job.run == "reference") {
          runs.reference = std::move(o.run);
          runs.referenceNote = o.note;
        } else if (job.run == "coarse") {
          runs.coarse = std::move(o.run);
        } else {
          runs.fine = std::move(o.run);
        }
      } catch (const std::exception& e) {
        runs.error += (runs.error.empty() ? "" : "; ") + job.run + ": " + e.what();
      }
    }
  }
  try {
    redis.command({"DEL", replies});
  } catch (const std::exception&) {
  }
  return out;
}

LocalWorkers::LocalWorkers(const std::string& redisUrl, const fs::path& dataDir, int count, bool pin) {
  const std::vector<int> cores = pin ? allowedCores() : std::vector<int>{};
  if (pin && cores.empty()) throw std::runtime_error("cannot pin the workers: this process's cores are unknown");
  char self[4096] = {};
  const ssize_t len = ::readlink("/proc/self/exe", self, sizeof self - 1);
  if (len <= 0) throw std::runtime_error("cannot find this executable (/proc/self/exe) to start workers");
  fs::create_directories(dataDir);
  for (int k = 1; k <= count; ++k) {
    const std::string log = (dataDir / ("worker-" + std::to_string(k) + ".log")).string();
    const std::string name = "bench-" + std::to_string(::getpid()) + "-" + std::to_string(k);
    std::vector<std::string> args = {self, "worker", "--redis", redisUrl, "--data", dataDir.string(), "--name", name};
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    const PinnedForSpawn pinned(pin ? cores[(k - 1) % cores.size()] : -1);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 2, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    pid_t pid = 0;
    const int rc = posix_spawn(&pid, self, &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (rc != 0) throw std::runtime_error("cannot start worker " + std::to_string(k) + ": " + std::strerror(rc));
    pids_.push_back(pid);
  }
}

LocalWorkers::~LocalWorkers() {
  for (int pid : pids_) ::kill(pid, SIGTERM);
  // An idle worker stops within a second; one still solving a cohort run (which has no cancel) is
  // given ten, then killed.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  for (int pid : pids_) {
    while (::waitpid(pid, nullptr, WNOHANG) == 0) {
      if (std::chrono::steady_clock::now() > deadline) {
        ::kill(pid, SIGKILL);
        ::waitpid(pid, nullptr, 0);
        break;
      }
      ::usleep(50000);
    }
  }
}

}  // namespace orthosim::cli
