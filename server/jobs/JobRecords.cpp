#include "jobs/JobRecords.hpp"

namespace orthosim::server {
using nlohmann::json;

namespace {

constexpr const char* kRecordLifetimeSeconds = "604800";  // a week

std::string recordKey(const std::string& job) { return "orthosim:job:" + job; }
std::string replicaSet(const std::string& replica) { return "orthosim:replica-jobs:" + replica; }

}  // namespace

void saveJobRecord(RedisConnection& redis, const std::string& replica, const JobRecord& r) {
  const std::string key = recordKey(r.job);
  redis.command({"HSET", key, "owner", r.owner, "case", r.caseId, "entry", r.entry, "context", r.context.dump()});
  redis.command({"EXPIRE", key, kRecordLifetimeSeconds});
  redis.command({"SADD", replicaSet(replica), r.job});
  redis.command({"EXPIRE", replicaSet(replica), kRecordLifetimeSeconds});
}

void setJobOwner(RedisConnection& redis, const std::string& job, const std::string& owner) {
  redis.command({"HSET", recordKey(job), "owner", owner});
}

void forgetJobRecord(RedisConnection& redis, const std::string& replica, const std::string& job) {
  redis.command({"SREM", replicaSet(replica), job});
  redis.command({"DEL", recordKey(job)});
}

std::vector<JobRecord> jobRecords(RedisConnection& redis, const std::string& replica) {
  std::vector<JobRecord> records;
  for (const RedisValue& member : redis.command({"SMEMBERS", replicaSet(replica)}).array) {
    const RedisValue fields = redis.command({"HGETALL", recordKey(member.string)});
    JobRecord r;
    r.job = member.string;
    for (std::size_t k = 0; k + 1 < fields.array.size(); k += 2) {
      const std::string& name = fields.array[k].string;
      const std::string& value = fields.array[k + 1].string;
      if (name == "owner") r.owner = value;
      if (name == "case") r.caseId = value;
      if (name == "entry") r.entry = value;
      if (name == "context") r.context = json::parse(value, nullptr, /*allow_exceptions=*/false);
    }
    if (r.owner.empty() || r.caseId.empty() || r.context.is_discarded()) {
      forgetJobRecord(redis, replica, r.job);
      continue;
    }
    records.push_back(std::move(r));
  }
  return records;
}

}  // namespace orthosim::server
