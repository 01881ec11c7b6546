#pragma once
// A fine job as it travels on the Redis stream (one field "job" holding this JSON), and what a
// worker reports back on the job's reply stream. docs/deployment.md "Past one machine".
//
//   {"format": "orthosim-job-1", "job": "<server id>-<n>", "kind": "fine", "case": "phantom-0",
//    "case_hash": "<hex>", "resolution": "fine", "reply_stream": "orthosim:replies:<server id>",
//    "plan": {"maxilla": {"translation_mm": [..3], "rotation_rad": [..3], "center_mm": [..3]}, ...}}
//
// A band job (kind "band") has "band": {..} besides (jobs/BandJobMessage); a cohort job (kind
// "cohort", `bench cohort --redis`) has "cohort": {..} (jobs/CohortJobMessage), its "case" is the
// patient's id and its plan is empty. Each kind has exactly its own fields.
//
// Numbers travel as JSON doubles printed to round-trip exactly, so a worker solves the very
// plan the server would have.
#include <Eigen/Core>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>

#include "jobs/BandJobMessage.hpp"
#include "jobs/CohortJobMessage.hpp"
#include "jobs/JobKind.hpp"
#include "scene/CaseFile.hpp"
#include "scene/Scene.hpp"

namespace orthosim::server {

inline constexpr const char* kJobFormat = "orthosim-job-1";

// A job message that is not one: what is wrong and where (a JSON pointer into the message).
class BadJobMessage : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

struct JobMessage {
  std::string job;  // unique over servers: "<server id>-<n>"
  JobKind kind = JobKind::fine;
  std::string caseId;
  std::string caseHash;  // caseContentHash() of the case the server planned on
  Resolution resolution = Resolution::Fine;
  std::string replyStream;  // where progress and the outcome go
  std::map<std::string, FragmentMotion> plan;
  std::optional<BandJobSpec> band;      // JobKind::band only
  std::optional<CohortJobSpec> cohort;  // JobKind::cohort only
};

std::string encodeJobMessage(const JobMessage& job);
// Throws BadJobMessage naming the defect (not JSON, another format, a missing or mistyped field,
// a non-finite number, a reply stream that is not this deployment's).
JobMessage decodeJobMessage(const std::string& text);

// The reply stream of a server and the cancel key of a job (both under the "orthosim:" prefix).
std::string replyStreamName(const std::string& serverId);
std::string cancelKey(const std::string& job);

// A hash of everything a solve of the case reads: the case file's bytes and every file it names
// (surfaces, volume mesh), in hex. Same inputs, same hash on any machine; an edited case (or an
// edited surface) gets another. Throws std::runtime_error when a file cannot be read.
std::string caseContentHash(const CaseSpec& spec);

// The stream fine jobs go on, and the consumer group of the workers that read it.
inline constexpr const char* kJobStream = "orthosim:jobs";
inline constexpr const char* kWorkerGroup = "orthosim-workers";

// The converged nodes of a job, as the worker leaves them in the data folder:
// "orthosim-nodes-1\n", the node count (uint64, little-endian), then x y z of each node (doubles).
// Written to a temporary name, flushed to disk and renamed: a reader sees all of it or nothing.
std::string resultFileName(const std::string& job);  // relative to the data folder: jobs/<job>.nodes
void writeResultNodes(const std::filesystem::path& file, const Eigen::Matrix3Xd& x);
// Throws std::runtime_error naming the file when it is missing, short, of another format, has
// another node count than `nodes`, or holds a non-finite number.
Eigen::Matrix3Xd readResultNodes(const std::filesystem::path& file, long long nodes);

}  // namespace orthosim::server
