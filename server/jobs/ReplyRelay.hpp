#pragma once
// The thread that reads a server's reply stream and hands each job's progress and outcome on: the
// job's record in jobs/JobRegistry, its outcome through jobs/JobOutcomes. Between reads it renews
// the replica's lease and cancels the orphans past their grace. Redis lost: every job out gets
// job_failed saying so, commands are refused at once (jobs/CommandConnection) and the relay
// connects again every second; when Redis answers, the command connection is renewed too.
#include <atomic>
#include <string>
#include <thread>

#include "jobs/CommandConnection.hpp"
#include "jobs/JobOutcomes.hpp"
#include "jobs/JobRegistry.hpp"
#include "jobs/ReplicaClaim.hpp"

namespace orthosim::server {

class ReplyRelay {
 public:
  // Starts the thread. With a replica's claim (null without a replica name) the replies read are
  // trimmed from the stream, so the replica's next run does not read them again.
  ReplyRelay(CommandConnection& commands, JobRegistry& registry, JobOutcomes& outcomes, std::string serverId,
             ReplicaClaim* claim);
  ~ReplyRelay() { stop(); }
  // Stops and joins the thread.
  void stop();

 private:
  void run();
  // One XREAD of the reply stream from `last` (moved past what was read).
  void readReplies(RedisConnection& redis, std::string& last);
  void handleReply(const std::string& text);
  void failAll(const std::string& why);

  CommandConnection& commands_;
  JobRegistry& registry_;
  JobOutcomes& outcomes_;
  const std::string serverId_;
  const std::string replyStream_;
  ReplicaClaim* const claim_;
  std::atomic<bool> stopping_{false};
  std::thread thread_;  // last: started once the rest exists
};

}  // namespace orthosim::server
