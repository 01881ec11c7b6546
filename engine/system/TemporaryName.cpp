#include "system/TemporaryName.hpp"

#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <random>

namespace orthosim {
namespace {

constexpr ino_t kInitialPidNamespace = 0xEFFFFFFCu;  // the kernel's PROC_PID_INIT_INO

}  // namespace

std::string hostName() {
  char name[256] = {};
  return ::gethostname(name, sizeof name - 1) == 0 ? name : "";
}

std::string temporaryHost() {
  static const std::string host = [] {
    std::string h = hostName();
    for (char& c : h)
      if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '.') c = '_';
    h = h.empty() ? std::string("host") : h.substr(0, 64);
    // Containers with the host's name (host networking) but pid namespaces of their own: their pids
    // mean nothing to each other, so each namespace but the first counts as a host of its own.
    struct stat ns {};
    if (::stat("/proc/self/ns/pid", &ns) == 0 && ns.st_ino != kInitialPidNamespace)
      h += "_pidns" + std::to_string(ns.st_ino);
    return h;
  }();
  return host;
}

std::string temporarySuffix() {
  static const std::string host = temporaryHost();
  static thread_local std::random_device device;
  static const char* digits = "0123456789abcdef";
  std::string random;
  for (int i = 0; i < 2; ++i) {
    const unsigned v = device();
    for (int k = 0; k < 8; ++k) random += digits[(v >> (4 * k)) & 0xf];
  }
  return host + "-" + std::to_string(::getpid()) + "-" + random;
}

std::optional<TemporaryWriter> temporaryWriter(std::string_view suffix) {
  // HOST-PID-RANDOM, read from the end: the host may hold '-' itself.
  constexpr std::size_t kRandom = 16;
  if (suffix.size() < kRandom + 4 || suffix[suffix.size() - kRandom - 1] != '-') return std::nullopt;
  for (const char c : suffix.substr(suffix.size() - kRandom))
    if (!std::isxdigit(static_cast<unsigned char>(c)) || std::isupper(static_cast<unsigned char>(c)))
      return std::nullopt;
  const std::string_view rest = suffix.substr(0, suffix.size() - kRandom - 1);
  const std::size_t dash = rest.rfind('-');
  if (dash == std::string_view::npos || dash == 0 || dash + 1 == rest.size() || rest.size() - dash - 1 > 9)
    return std::nullopt;
  long pid = 0;
  for (const char c : rest.substr(dash + 1)) {
    if (!std::isdigit(static_cast<unsigned char>(c))) return std::nullopt;
    pid = pid * 10 + (c - '0');
  }
  if (pid <= 0) return std::nullopt;
  TemporaryWriter writer{std::string(rest.substr(0, dash)), pid};
  for (const char c : writer.host)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '.' && c != '_') return std::nullopt;
  return writer;
}

WriterState writerState(const TemporaryWriter& writer) {
  if (writer.host != temporaryHost()) return WriterState::Unknown;
  // Signal 0 checks the pid without sending anything; EPERM: a process of another user has it.
  if (::kill(static_cast<pid_t>(writer.pid), 0) == 0 || errno != ESRCH) return WriterState::Running;
  return WriterState::Gone;
}

}  // namespace orthosim
