#include "jobs/JobNumbers.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <string>

namespace orthosim::server {
namespace fs = std::filesystem;

namespace {

constexpr const char* kCounterKey = "orthosim:job-number";
// The counter raised to the floor when it is below it (or missing: Redis lost it), then INCR; one
// script, so no other server's INCR comes in between.
constexpr const char* kNextNumberScript =
    "local n = tonumber(redis.call('GET', KEYS[1]) or '0') "
    "if n == nil or n < tonumber(ARGV[1]) then redis.call('SET', KEYS[1], ARGV[1]) end "
    "return redis.call('INCR', KEYS[1])";

// The record open and flocked (shared or exclusive) for as long as this lives.
class LockedRecord {
 public:
  LockedRecord(const fs::path& file, int operation) : file_(file) {
    fd_ = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0) fail("cannot be opened");
    while (::flock(fd_, operation) != 0)
      if (errno != EINTR) fail("cannot be locked");
  }
  ~LockedRecord() { ::close(fd_); }  // releases the flock
  LockedRecord(const LockedRecord&) = delete;
  LockedRecord& operator=(const LockedRecord&) = delete;

  // The number recorded; 0 when the file is new (empty).
  long long read() const {
    char text[64];
    const ssize_t n = ::pread(fd_, text, sizeof text - 1, 0);
    if (n < 0) fail("cannot be read");
    std::string s(text, static_cast<std::size_t>(n));
    while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
    if (s.empty()) return 0;
    if (s.size() > 18 || s.find_first_not_of("0123456789") != std::string::npos)  // 18 digits: below 2^63
      throw JobNumberRecordError(file_.string() + " holds no job number ('" + s.substr(0, 20) +
                                 "'): put the highest job number issued there, or remove it only when Redis "
                                 "still has its counter");
    return std::stoll(s);
  }

  // Fixed width, one write at the start of the file: a reader under the lock sees one number whole.
  void write(long long number) const {
    std::string s = std::to_string(number);
    s = std::string(18 - std::min<std::size_t>(18, s.size()), '0') + s + "\n";
    if (::pwrite(fd_, s.data(), s.size(), 0) != static_cast<ssize_t>(s.size())) fail("cannot be written");
    if (::ftruncate(fd_, static_cast<off_t>(s.size())) != 0 || ::fdatasync(fd_) != 0) fail("cannot be written");
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw JobNumberRecordError("the job number record " + file_.string() + " " + what + ": " + std::strerror(errno));
  }

  fs::path file_;
  int fd_ = -1;
};

}  // namespace

JobNumbers::JobNumbers(const fs::path& dataDir) : file_(dataDir / "orthosim.job-number") {}

long long JobNumbers::next(RedisConnection& redis) {
  long long floor = highest_;
  {
    const LockedRecord record(file_, LOCK_SH);
    floor = std::max(floor, record.read());
  }
  const long long number = redis.command({"EVAL", kNextNumberScript, "1", kCounterKey, std::to_string(floor)}).integer;
  if (number <= floor)  // only a counter that is not a number could do this
    throw RedisCommandError("Redis at " + redis.address().text + " gave job number " + std::to_string(number) +
                            ", not above " + std::to_string(floor));
  {  // recorded before anyone sees it, never lowered (another server may have gone further meanwhile)
    const LockedRecord record(file_, LOCK_EX);
    if (record.read() < number) record.write(number);
  }
  highest_ = number;
  return number;
}

}  // namespace orthosim::server
