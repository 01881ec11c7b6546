#pragma once
// The suffix of a file written beside its target and renamed into place. Several processes on
// several machines may write into one folder (server replicas and workers sharing a data folder
// over a network file system; containers, where every server is pid 1): the process id alone is
// not unique there, so the suffix is the host name, the pid and 64 random bits, e.g.
// "node-a-4242-3f9c0e1d2b7a6c58".
#include <string>

namespace orthosim {

// This machine's host name as gethostname gives it; empty when it has none.
std::string hostName();

// Unique across hosts, processes, threads and calls; only letters, digits, '-' and '.'.
std::string temporarySuffix();

}  // namespace orthosim
