#pragma once
// What an interrupted server leaves in its data folder: plan files half-saved when it was killed
// (plans/<case>/<name>.json.tmp<suffix>) and case folders half-written when a write failed
// (cases/<id>.writing-<suffix>/), imported patients half-written (patients/.<id>.importing-<suffix>/)
// and the uploads staged for an import (imports/*); <suffix> is mesh/TemporaryName's. None is ever
// read; a process that starts with the folder to itself (DataFolderLock::alone()) removes them,
// since no other process can be writing them. With replicas or workers running, they stay.
#include <filesystem>
#include <string>
#include <vector>

namespace orthosim::server {

// Removes the leftovers under `dataDir`; returns what it removed (paths relative to dataDir).
std::vector<std::string> removeLeftovers(const std::filesystem::path& dataDir);

}  // namespace orthosim::server
