#pragma once
// What an interrupted server leaves in its data folder: plan files half-saved when it was killed
// (plans/<case>/<name>.json.tmp<pid>-<n>) and case folders half-written when a write failed
// (cases/<id>.writing-<pid>/), imported patients half-written (patients/.<id>.importing-<pid>/)
// and the uploads staged for an import (imports/*). None is ever read; the server that holds the folder's lock
// (DataFolderLock) removes them at start, since no other process can be writing them.
#include <filesystem>
#include <string>
#include <vector>

namespace orthosim::server {

// Removes the leftovers under `dataDir`; returns what it removed (paths relative to dataDir).
std::vector<std::string> removeLeftovers(const std::filesystem::path& dataDir);

}  // namespace orthosim::server
