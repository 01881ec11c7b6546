#pragma once
// The suffix of a file written beside its target and renamed into place. Several processes on
// several machines may write into one folder (server replicas and workers sharing a data folder
// over a network file system; containers, where every server is pid 1): the process id alone is
// not unique there, so the suffix is the host name, the pid and 64 random bits, e.g.
// "node-a-4242-3f9c0e1d2b7a6c58". A process in a pid namespace of its own (a container) adds the
// namespace to its host ("node-a_pidns4026532201"): the pid is then only meaningful inside it.
// The suffix names the writer, so that what an interrupted writer left can be told from what a
// live one is writing (the server's DataFolderLeftovers).
#include <optional>
#include <string>
#include <string_view>

namespace orthosim {

// This machine's host name as gethostname gives it; empty when it has none.
std::string hostName();

// Unique across hosts, processes, threads and calls; only letters, digits, '-' and '.'.
std::string temporarySuffix();

// The process a temporary file's suffix names: who may still be writing it.
struct TemporaryWriter {
  std::string host;  // as temporarySuffix() spells it
  long pid = 0;
};

// The writer named by `suffix` (what follows a temporary file's marker, e.g. ".tmp"), or nullopt
// when temporarySuffix() did not make it (another name, or one from an older version).
std::optional<TemporaryWriter> temporaryWriter(std::string_view suffix);

enum class WriterState {
  Running,  // on this host, and its pid is in use
  Gone,     // on this host, and no process has its pid
  Unknown,  // on another host: its processes cannot be seen from here
};

// Whether a temporary file's writer still runs. A pid taken over by another process since reads as
// Running: its file is then kept, never removed under a live writer.
WriterState writerState(const TemporaryWriter& writer);

// This host as temporarySuffix() spells it.
std::string temporaryHost();

}  // namespace orthosim
