// Redis stopped and started again empty (no persistence, as the test redis-server runs): the first
// confirm once the server has Redis back is queued, a command connection Redis closed is opened
// again for the next confirm, and job numbers never repeat, not over a Redis restart, not over a
// server restart on the same data folder, not between two servers sharing Redis and the folder.
#include <gtest/gtest.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "../server/ServerProcess.hpp"
#include "../server/WsTestClient.hpp"
#include "RedisJobsFixture.hpp"
#include "RedisTestServer.hpp"
#include "TestWait.hpp"
#include "jobs/JobMessage.hpp"
#include "jobs/JobNumbers.hpp"
#include "jobs/RedisConnection.hpp"

namespace orthosim {
namespace {
namespace fs = std::filesystem;
using nlohmann::json;
using namespace std::chrono_literals;

std::size_t occurrences(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// Until the server's log has said `times` times that Redis is back (the relay reconnected).
bool waitForRedisBack(const std::string& log, std::size_t times) {
  return test::waitUntil([&] { return occurrences(test::readFile(test::redisLogFile(log)), "is back") >= times; }, 30s,
                         50ms);
}

long long queuedJob(test::WsTestClient& ws) {
  const json queued = ws.request({{"type", "confirm"}});
  EXPECT_EQ(queued["type"], "job_queued") << queued.dump();
  return queued.value("job", -1LL);
}

// A folder of its own, for job number records.
fs::path freshFolder(const std::string& name) {
  const fs::path dir = fs::path(test::testDataDir()).parent_path() / (name + "-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(RedisRestart, TheFirstConfirmOnceRedisIsBackIsQueued) {
  REQUIRE_REDIS_SERVER();
  test::RedisTestServer redis;
  const std::string log = "first-confirm-serve";
  test::ServerProcess server({"--redis", redis.url()}, test::redisLogFile(log).string());
  test::WsTestClient ws(server.port());
  test::openPhantomAdvanced(ws, 4);
  const long long before = queuedJob(ws);  // no worker: it waits on the stream
  redis.kill();
  test::jobMessage(ws, before, "job_failed", 30s);  // the server has seen Redis go
  redis.restart();
  ASSERT_TRUE(waitForRedisBack(log, 1)) << test::readFile(test::redisLogFile(log));
  const json queued = ws.request({{"type", "confirm"}});
  ASSERT_EQ(queued["type"], "job_queued") << "the first confirm after Redis came back: " << queued.dump();
  server::RedisConnection c(server::parseRedisUrl(redis.url()));
  EXPECT_EQ(c.command({"XLEN", server::kJobStream}).integer, 1) << "the job is on the new Redis";
}

TEST(RedisRestart, ACommandConnectionRedisClosedIsOpenedAgainForTheNextConfirm) {
  REQUIRE_REDIS_SERVER();
  test::RedisTestServer redis;
  test::ServerProcess server({"--redis", redis.url()}, test::redisLogFile("closed-connection-serve").string());
  test::WsTestClient ws(server.port());
  test::openPhantomAdvanced(ws, 4);
  const long long first = queuedJob(ws);
  // Redis closes the server's command connection (as its idle `timeout` does); the relay's stays.
  server::RedisConnection c(server::parseRedisUrl(redis.url()));
  std::string id;
  std::istringstream clients(c.command({"CLIENT", "LIST"}).string);
  for (std::string line; std::getline(clients, line);)
    if (line.find("cmd=xinfo") != std::string::npos) id = line.substr(3, line.find(' ') - 3);  // "id=N ..."
  ASSERT_FALSE(id.empty()) << "the command connection's last command was XINFO";
  ASSERT_EQ(c.command({"CLIENT", "KILL", "ID", id}).integer, 1);
  const long long second = queuedJob(ws);
  EXPECT_GT(second, first);
  EXPECT_EQ(c.command({"XLEN", server::kJobStream}).integer, 2) << "each job queued once";
}

TEST(RedisRestart, JobNumbersAreNeverReusedAfterRedisComesBackEmpty) {
  REQUIRE_REDIS_SERVER();
  test::RedisTestServer redis;
  std::vector<long long> numbers;
  {
    const std::string log = "numbers-serve-1";
    test::ServerProcess server({"--redis", redis.url()}, test::redisLogFile(log).string());
    test::WsTestClient ws(server.port());
    test::openPhantomAdvanced(ws, 4);
    numbers.push_back(queuedJob(ws));
    numbers.push_back(queuedJob(ws));
    redis.restart();  // empty: the counter is gone
    ASSERT_TRUE(waitForRedisBack(log, 1)) << test::readFile(test::redisLogFile(log));
    numbers.push_back(queuedJob(ws));
    ASSERT_EQ(server.stop(SIGTERM, 20s), 0);
  }
  redis.restart();  // empty again, and a new server process on the same data folder
  test::ServerProcess server({"--redis", redis.url()}, test::redisLogFile("numbers-serve-2").string());
  test::WsTestClient ws(server.port());
  test::openPhantomAdvanced(ws, 4);
  numbers.push_back(queuedJob(ws));
  for (std::size_t i = 1; i < numbers.size(); ++i)
    EXPECT_GT(numbers[i], numbers[i - 1]) << "job " << i << " of " << json(numbers).dump();
  EXPECT_GE(numbers.front(), server::kFirstRedisJobNumber);
}

// Two servers on one Redis and one data folder (what replicas share), as JobNumbers objects with
// a connection each: interleaved, over a Redis restart, over a counter restored from an older
// backup, every number is new. With a floor kept in each server's memory only, the server that
// issued fewer numbers would start again inside the other's after the restart.
TEST(RedisRestart, TwoServersSharingRedisNeverIssueTheSameNumber) {
  REQUIRE_REDIS_SERVER();
  test::RedisTestServer redis;
  const fs::path data = freshFolder("job-numbers");
  server::JobNumbers a(data), b(data);
  std::vector<long long> issued;
  auto next = [&](server::JobNumbers& numbers) {
    server::RedisConnection c(server::parseRedisUrl(redis.url()));
    issued.push_back(numbers.next(c));
  };
  next(b);
  next(a);
  next(a);
  next(a);
  redis.restart();
  next(b);  // b has issued less than a: its own floor is below a's numbers
  next(a);
  next(b);
  {  // Redis restored from an older backup: the counter is behind
    server::RedisConnection c(server::parseRedisUrl(redis.url()));
    c.command({"SET", "orthosim:job-number", std::to_string(issued.front())});
  }
  next(a);
  next(b);
  EXPECT_EQ(std::set<long long>(issued.begin(), issued.end()).size(), issued.size()) << json(issued).dump();
  const long long highest = *std::max_element(issued.begin(), issued.end());
  EXPECT_EQ(std::stoll(test::readFile(data / "orthosim.job-number")), highest) << "the record holds the highest";
  // A third server started later on the folder, Redis empty again: above them all too.
  redis.restart();
  server::JobNumbers later(data);
  server::RedisConnection c(server::parseRedisUrl(redis.url()));
  EXPECT_GT(later.next(c), highest);
  fs::remove_all(data);
}

TEST(RedisRestart, AnUnreadableNumberRecordIsRefusedAndIssuesNothing) {
  REQUIRE_REDIS_SERVER();
  test::RedisTestServer redis;
  const fs::path data = freshFolder("job-numbers-bad");
  std::ofstream(data / "orthosim.job-number") << "twelve\n";
  server::JobNumbers numbers(data);
  server::RedisConnection c(server::parseRedisUrl(redis.url()));
  try {
    numbers.next(c);
    ADD_FAILURE() << "a number issued without knowing the highest issued before";
  } catch (const server::JobNumberRecordError& e) {
    EXPECT_NE(std::string(e.what()).find("holds no job number"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(c.command({"GET", "orthosim:job-number"}).isNil()) << "the counter untouched";
  fs::remove_all(data);
}

}  // namespace
}  // namespace orthosim
