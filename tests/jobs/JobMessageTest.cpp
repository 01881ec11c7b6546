// The fine job as it travels on Redis (jobs/JobMessage): a round trip keeps the plan bit for bit;
// malformed and foreign messages are refused naming what is wrong; the case hash follows the
// case's files; the result file is all or nothing.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "jobs/JobMessage.hpp"
#include "jobs/RedisConnection.hpp"
#include "phantom/PhantomCase.hpp"

namespace orthosim::server {
namespace {
namespace fs = std::filesystem;
using nlohmann::json;

JobMessage sample() {
  JobMessage m;
  m.job = "0123456789abcdef-7";
  m.caseId = "phantom-0";
  m.caseHash = "00ff00ff00ff00ff";
  m.replyStream = replyStreamName("0123456789abcdef");
  FragmentMotion maxilla;
  maxilla.translation = {-4.000000000000001, 0.1, 1.0 / 3.0};
  maxilla.rotation = {0, 0.0174532925199433, -1e-17};
  maxilla.center = {-71.25, 0, -38.5};
  m.plan["maxilla"] = maxilla;
  m.plan["mandible_distal"] = FragmentMotion{};
  return m;
}

std::string withField(const std::string& key, const json& value) {
  json j = json::parse(encodeJobMessage(sample()));
  if (value.is_null())
    j.erase(key);
  else
    j[key] = value;
  return j.dump();
}

void expectRefused(const std::string& text, const std::string& mentions) {
  try {
    decodeJobMessage(text);
    ADD_FAILURE() << "accepted: " << text;
  } catch (const BadJobMessage& e) {
    EXPECT_NE(std::string(e.what()).find(mentions), std::string::npos) << e.what();
  }
}

TEST(JobMessage, RoundTripKeepsThePlanBitForBit) {
  const JobMessage in = sample();
  const JobMessage out = decodeJobMessage(encodeJobMessage(in));
  EXPECT_EQ(out.job, in.job);
  EXPECT_EQ(out.caseId, in.caseId);
  EXPECT_EQ(out.caseHash, in.caseHash);
  EXPECT_EQ(out.replyStream, in.replyStream);
  EXPECT_EQ(out.resolution, Resolution::Fine);
  ASSERT_EQ(out.plan.size(), in.plan.size());
  for (const auto& [name, m] : in.plan) {
    ASSERT_TRUE(out.plan.count(name)) << name;
    EXPECT_EQ(out.plan.at(name).translation, m.translation) << name;  // exact: no rounding on the way
    EXPECT_EQ(out.plan.at(name).rotation, m.rotation) << name;
    EXPECT_EQ(out.plan.at(name).center, m.center) << name;
  }
}

TEST(JobMessage, MalformedAndForeignMessagesAreRefusedSayingWhere) {
  expectRefused("", "not JSON");
  expectRefused("{\"format\": ", "not JSON");
  expectRefused("[1, 2]", "JSON object");
  expectRefused(withField("format", "celery-task-2"), "/format");
  expectRefused(withField("format", nullptr), "/format: required");
  expectRefused(withField("job", "../../etc/passwd"), "/job");
  expectRefused(withField("kind", "celery"), "/kind");
  expectRefused(withField("case", "Phantom 0!"), "/case");
  expectRefused(withField("case_hash", "xyz"), "/case_hash");
  expectRefused(withField("resolution", "ultra"), "/resolution");
  expectRefused(withField("reply_stream", "someone:else"), "/reply_stream");
  expectRefused(withField("plan", nullptr), "/plan: required");
  expectRefused(withField("plan", json::array()), "/plan");
  expectRefused(withField("plan", {{"maxilla", {{"translation_mm", {1, 2}}}}}), "/plan/maxilla/rotation_rad: required");
  expectRefused(
      withField("plan",
                {{"maxilla", {{"translation_mm", {1, 2}}, {"rotation_rad", {0, 0, 0}}, {"center_mm", {0, 0, 0}}}}}),
      "/plan/maxilla/translation_mm: must be an array of 3");
  expectRefused(
      withField("plan", {{"maxilla",
                          {{"translation_mm", {1, 2, "x"}}, {"rotation_rad", {0, 0, 0}}, {"center_mm", {0, 0, 0}}}}}),
      "/plan/maxilla/translation_mm/2");
  expectRefused(withField("priority", 1), "/priority: unknown");
  // A NaN cannot be written as JSON: it arrives as null and is refused as not a number.
  JobMessage nan = sample();
  nan.plan["maxilla"].translation.x() = std::nan("");
  expectRefused(encodeJobMessage(nan), "/plan/maxilla/translation_mm/0");
}

TEST(JobMessage, TheCaseHashFollowsTheCaseFiles) {
  const fs::path dir = fs::temp_directory_path() / ("orthosim-jobhash-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  writePhantomCase(0, dir.string());
  const CaseSpec spec = loadCaseFile((dir / "case.json").string());
  const std::string before = caseContentHash(spec);
  EXPECT_EQ(before.size(), 16u);
  EXPECT_EQ(caseContentHash(loadCaseFile((dir / "case.json").string())), before) << "same files, same hash";
  {
    std::ofstream out(spec.bones.back().surface, std::ios::app);
    out << "\n";  // one byte more in a bone surface
  }
  EXPECT_NE(caseContentHash(spec), before);
  fs::remove(spec.bones.back().surface);
  EXPECT_THROW(caseContentHash(spec), std::runtime_error);
  fs::remove_all(dir);
}

TEST(JobMessage, ResultNodesAreWrittenWholeAndCheckedOnReading) {
  const fs::path dir = fs::temp_directory_path() / ("orthosim-jobnodes-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  Eigen::Matrix3Xd x = Eigen::Matrix3Xd::Random(3, 1000);
  const fs::path file = dir / resultFileName("abc-1");
  writeResultNodes(file, x);
  EXPECT_EQ(readResultNodes(file, 1000), x);
  for (const auto& e : fs::directory_iterator(file.parent_path()))
    EXPECT_EQ(e.path(), file) << "no temporary file left behind";
  EXPECT_THROW(readResultNodes(file, 999), std::runtime_error) << "another node count";
  fs::resize_file(file, fs::file_size(file) - 8);
  EXPECT_THROW(readResultNodes(file, 1000), std::runtime_error) << "truncated";
  EXPECT_THROW(readResultNodes(dir / "missing.nodes", 1000), std::runtime_error);
  fs::remove_all(dir);
}

TEST(JobMessage, RedisAddressesAreCheckedBeforeConnecting) {
  const RedisAddress a = parseRedisUrl("redis://10.0.0.5:6380");
  EXPECT_EQ(a.host, "10.0.0.5");
  EXPECT_EQ(a.port, 6380);
  EXPECT_EQ(parseRedisUrl("redis://queue").port, 6379);
  for (const char* bad : {"http://queue:6379", "queue:6379", "redis://", "redis://:6379", "redis://q:0",
                          "redis://q:99999", "redis://q:x", "redis://user:pw@q:6379", "redis://q:6379/2"})
    EXPECT_THROW(parseRedisUrl(bad), std::invalid_argument) << bad;
  // Nobody listens on port 1: a clear error naming the address, no hang.
  try {
    RedisConnection c(parseRedisUrl("redis://127.0.0.1:1"));
    ADD_FAILURE() << "connected to port 1";
  } catch (const RedisUnavailable& e) {
    EXPECT_NE(std::string(e.what()).find("redis://127.0.0.1:1"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace orthosim::server
