#include "jobs/RedisWorker.hpp"

#include <unistd.h>

#include <iostream>
#include <optional>
#include <thread>

#include "cases/PatientImport.hpp"
#include "jobs/BandWorkerJob.hpp"
#include "jobs/CohortWorkerJob.hpp"
#include "jobs/FineJob.hpp"
#include "jobs/JobStream.hpp"
#include "system/TemporaryName.hpp"

namespace orthosim::server {
using nlohmann::json;
using namespace std::chrono_literals;
namespace fs = std::filesystem;

namespace {

void say(const std::string& line) { std::cerr << ("orthosim worker: " + line + "\n") << std::flush; }

std::string defaultName() { return hostName() + "-" + std::to_string(::getpid()); }

// The entries of an XREADGROUP or XAUTOCLAIM reply: [[id, [field, value, ...]], ...].
const std::vector<RedisValue>* entriesOf(const RedisValue& r, bool autoclaim) {
  if (r.kind != RedisValue::Kind::Array) return nullptr;
  if (autoclaim) return r.array.size() >= 2 ? &r.array[1].array : nullptr;
  if (r.array.empty() || r.array[0].array.size() < 2) return nullptr;
  return &r.array[0].array[1].array;
}

void sendReply(RedisConnection& redis, const std::string& stream, const json& message) {
  redis.command({"XADD", stream, "MAXLEN", "~", "1000", "*", "msg", message.dump()});
}

}  // namespace

RedisWorker::RedisWorker(WorkerOptions options)
    : options_(std::move(options)), cases_(options_.cases, options_.dataDir, options_.modelMemoryBytes) {
  if (options_.name.empty()) options_.name = defaultName();
  std::vector<std::string> skipped;
  for (const CaseEntry& c : PatientImporter::imported(options_.dataDir, &skipped)) try {
      cases_.add(c);
    } catch (const std::invalid_argument&) {
    }
  RedisConnection redis(options_.redis);
  ensureWorkerGroup(redis);
}

void RedisWorker::run(const std::atomic<bool>& stop) {
  std::vector<std::thread> threads;
  for (int i = 0; i < std::max(1, options_.concurrency); ++i)
    threads.emplace_back([this, i, &stop] { serve(i, stop); });
  for (std::thread& t : threads) t.join();
}

void RedisWorker::serve(int thread, const std::atomic<bool>& stop) {
  const std::string consumer = options_.name + "-" + std::to_string(thread);
  const std::string idleMs = std::to_string(options_.visibilityTimeout.count());
  std::unique_ptr<RedisConnection> redis;
  bool lost = false;
  while (!stop) {
    try {
      if (!redis) {
        redis = std::make_unique<RedisConnection>(options_.redis);
        redis->setTimeout(10s);
        ensureWorkerGroup(*redis);
        if (lost) say("Redis at " + options_.redis.text + " is back");
        lost = false;
      }
      // First a job whose worker stopped claiming it (died) for longer than the visibility timeout.
      RedisValue r = redis->command({"XAUTOCLAIM", kJobStream, kWorkerGroup, consumer, idleMs, "0-0", "COUNT", "1"});
      const std::vector<RedisValue>* entries = entriesOf(r, true);
      bool reclaimed = entries && !entries->empty();
      if (!reclaimed) {
        r = redis->command(
            {"XREADGROUP", "GROUP", kWorkerGroup, consumer, "COUNT", "1", "BLOCK", "1000", "STREAMS", kJobStream, ">"});
        entries = entriesOf(r, false);
      }
      if (!entries) continue;
      for (const RedisValue& entry : *entries) {
        if (reclaimed && !entry.array.empty())
          say("took over " + entry.array[0].string + " from a worker that stopped");
        handle(*redis, consumer, entry, stop);
      }
    } catch (const RedisUnavailable& e) {
      redis.reset();
      if (!lost) say(std::string(e.what()) + "; trying again every second");
      lost = true;
      for (int i = 0; i < 10 && !stop; ++i) std::this_thread::sleep_for(100ms);
    } catch (const RedisCommandError& e) {
      say(e.what());
      for (int i = 0; i < 10 && !stop; ++i) std::this_thread::sleep_for(100ms);
    }
  }
}

void RedisWorker::acknowledge(RedisConnection& redis, const std::string& entryId) {
  redis.command({"XACK", kJobStream, kWorkerGroup, entryId});
  redis.command({"XDEL", kJobStream, entryId});
}

void RedisWorker::refuse(RedisConnection& redis, const std::string& entryId, const std::string& replyStream,
                         const std::string& job, const std::string& why) {
  say("refused stream entry " + entryId + (job.empty() ? "" : " (job " + job + ")") + ": " + why);
  if (!replyStream.empty() && !job.empty())
    sendReply(redis, replyStream,
              {{"type", "job_failed"}, {"job", job}, {"message", "the worker refused the job: " + why}});
  acknowledge(redis, entryId);
}

void RedisWorker::checkCase(const JobMessage& job) {
  if (!cases_.find(job.caseId)) {  // imported since this worker started?
    for (const CaseEntry& c : PatientImporter::imported(options_.dataDir, nullptr)) try {
        cases_.add(c);
      } catch (const std::invalid_argument&) {
      }
    if (!cases_.find(job.caseId))
      throw std::runtime_error("the case '" + job.caseId + "' is not in the data folder " + options_.dataDir.string() +
                               " nor among this worker's cases");
  }
  const std::string hash = caseContentHash(cases_.spec(job.caseId));
  if (hash != job.caseHash)
    throw std::runtime_error("the case '" + job.caseId + "' in " + options_.dataDir.string() + " (hash " + hash +
                             ") is not the one the job was planned on (hash " + job.caseHash +
                             "): it was edited since, or the server uses another data folder");
  const std::lock_guard<std::mutex> lock(mutex_);
  auto it = builtHash_.find(job.caseId);
  if (it != builtHash_.end() && it->second != hash) cases_.invalidate(job.caseId);
  builtHash_[job.caseId] = hash;
}

std::optional<json> RedisWorker::runFine(const JobMessage& job, const std::atomic<bool>& cancel,
                                         const JobReport& report) {
  std::optional<FineSolve> solved = runFineJob(0, cases_, job.caseId, job.plan, cancel, report);
  if (!solved) return std::nullopt;
  try {
    writeResultNodes(options_.dataDir / resultFileName(job.job), solved->x);
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string("its result cannot be written: ") + e.what());
  }
  return json{{"type", "job_done"},
              {"figures", solved->figures},
              {"result", resultFileName(job.job)},
              {"nodes", solved->x.cols()}};
}

void RedisWorker::handle(RedisConnection& redis, const std::string& consumer, const RedisValue& entry,
                         const std::atomic<bool>& stop) {
  if (entry.array.empty()) return;
  const std::string entryId = entry.array[0].string;
  std::optional<std::string> raw;
  if (entry.array.size() >= 2)
    for (size_t k = 0; k + 1 < entry.array[1].array.size(); k += 2)
      if (entry.array[1].array[k].string == "job") raw = entry.array[1].array[k + 1].string;
  if (!raw) {
    refuse(redis, entryId, "", "", "not a job: the entry has no field 'job'");
    return;
  }
  JobMessage job;
  try {
    job = decodeJobMessage(*raw);
  } catch (const BadJobMessage& e) {
    // Answered only when the message names a job and one of our reply streams.
    std::string replyStream, name;
    try {
      const json j = json::parse(*raw);
      const std::string stream = j.value("reply_stream", ""), candidate = j.value("job", "");
      if (stream.rfind("orthosim:replies:", 0) == 0 && stream.size() < 200 && candidate.size() < 200) {
        replyStream = stream;
        name = candidate;
      }
    } catch (const std::exception&) {
    }
    refuse(redis, entryId, replyStream, name, std::string("not a job: ") + e.what());
    return;
  }
  if (redis.command({"EXISTS", cancelKey(job.job)}).integer > 0) {
    say("job " + job.job + " was cancelled before it started");
    sendReply(redis, job.replyStream, {{"type", "job_cancelled"}, {"job", job.job}, {"phase", "queued"}});
    acknowledge(redis, entryId);
    return;
  }
  try {
    if (job.kind != JobKind::cohort) checkCase(job);  // a cohort job's case is written by runCohortOnWorker
  } catch (const std::exception& e) {
    refuse(redis, entryId, job.replyStream, job.job, e.what());
    return;
  }
  say(std::string(jobKindWord(job.kind)) + " job " + job.job + ": case " + job.caseId + " on " + consumer);

  std::atomic<bool> cancel{false}, abandoned{false}, finished{false}, replyLost{false};
  // Cancel key and keeping the entry: on its own connection, so the solve is never waited on.
  std::thread watcher([&] {
    std::unique_ptr<RedisConnection> w;
    auto lastClaim = std::chrono::steady_clock::now();
    while (!finished) {
      if (stop) {
        abandoned = true;
        cancel = true;
      }
      try {
        if (!w) w = std::make_unique<RedisConnection>(options_.redis, 1000ms);
        if (w->command({"EXISTS", cancelKey(job.job)}).integer > 0) cancel = true;
        if (std::chrono::steady_clock::now() - lastClaim > options_.visibilityTimeout / 3) {
          w->command({"XCLAIM", kJobStream, kWorkerGroup, consumer, "0", entryId, "JUSTID"});
          lastClaim = std::chrono::steady_clock::now();
        }
      } catch (const std::exception&) {
        w.reset();  // Redis away: the job goes on; its reply will tell
      }
      std::this_thread::sleep_for(100ms);
    }
  });
  const JobReport report = [&](json message) {
    if (abandoned || replyLost) return;
    message["job"] = job.job;
    try {
      sendReply(redis, job.replyStream, message);
    } catch (const std::exception& e) {
      replyLost = true;
      cancel = true;  // nobody hears about it: stop, and leave the entry for a worker that can answer
    }
  };
  std::optional<json> done;  // the job_done message, its result written
  std::string failure;
  try {
    switch (job.kind) {
      case JobKind::band:
        done = runBandOnWorker(job, cases_, options_.dataDir, cancel, report);
        break;
      case JobKind::cohort:
        done = runCohortOnWorker(job, options_.dataDir, consumer);
        break;
      case JobKind::fine:
        done = runFine(job, cancel, report);
        break;
    }
  } catch (const std::exception& e) {
    failure = e.what();
  }
  finished = true;
  watcher.join();
  if (abandoned) {
    say("job " + job.job + " left for another worker (stopping)");
    return;
  }
  if (replyLost) throw RedisUnavailable("lost Redis at " + options_.redis.text + " during job " + job.job);
  if (!failure.empty()) {
    say("job " + job.job + " failed: " + failure);
    const std::string kind = jobKindWord(job.kind);
    json failed = {{"type", "job_failed"}, {"message", "the " + kind + " job failed: " + failure}};
    if (job.kind != JobKind::fine) failed["kind"] = kind;
    report(failed);
  } else if (!done && cancel) {
    say("job " + job.job + " cancelled");
  } else if (done) {
    report(*done);
    say("job " + job.job + " done");
  }
  if (replyLost) throw RedisUnavailable("lost Redis at " + options_.redis.text + " during job " + job.job);
  acknowledge(redis, entryId);  // only now: the result is on disk and the server told
}

}  // namespace orthosim::server
