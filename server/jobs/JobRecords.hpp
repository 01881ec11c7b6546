#pragma once
// What a server keeps on Redis about each fine job it queued, so that the server started again
// under the same replica name finds them (docs/deployment.md, "Nothing lost"): the hash
// orthosim:job:<job> (session, case, stream entry, the session's context) and the set
// orthosim:replica-jobs:<replica> of the replica's jobs. A record goes when its job's outcome has
// reached a session or the job is cancelled; records expire after a week whatever happens.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "jobs/RedisConnection.hpp"

namespace orthosim::server {

struct JobRecord {
  std::string job;    // "<replica>-<number>"
  std::string owner;  // the session that queued it, or took it over (resume)
  std::string caseId;
  std::string entry;       // the job stream's entry id
  nlohmann::json context;  // what the session needs to publish the outcome (its poses)
};

void saveJobRecord(RedisConnection& redis, const std::string& replica, const JobRecord& record);
void setJobOwner(RedisConnection& redis, const std::string& job, const std::string& owner);
void forgetJobRecord(RedisConnection& redis, const std::string& replica, const std::string& job);
// The replica's records; members whose record expired or cannot be read are dropped from its set.
std::vector<JobRecord> jobRecords(RedisConnection& redis, const std::string& replica);

}  // namespace orthosim::server
