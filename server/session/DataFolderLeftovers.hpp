#pragma once
// What an interrupted writer leaves in its data folder. Every write there goes through a temporary
// name carrying system/TemporaryName's suffix (HOST-PID-RANDOM), which names its writer:
//   cases/<id>.writing-<suffix>/ and cases/<id>/case.json.writing-<suffix>   built cases
//   patients/.<id>.importing-<suffix>/, patients/<id>/.case.json.editing-<suffix>   imports, edits
//   imports/<id>.upload-<suffix>/ and the rest of imports/ (uploads and scans staged for an import)
//   plans/<case>/<name>.json.tmp<suffix>, cache/<key>.tissue.tmp<suffix>
//   jobs/<job>.nodes.part-<suffix>, jobs/<job>.band.json.tmp<suffix>, jobs/<job>.cohort.json.tmp<suffix>
// None is ever read. A starting server or worker removes those whose writer is gone: it ran on this
// host and its pid is free (or is this process's own: a former run of it, as pid 1 in a container
// is). One from another host, or whose name names no writer (older versions, staged scans), is
// removed only by a process that has the folder to itself (DataFolderLock::alone()): otherwise a
// replica elsewhere may be writing it. A file whose writer runs is never removed.
#include <filesystem>
#include <string>
#include <vector>

namespace orthosim::server {

// Removes the leftovers under `dataDir`; `alone`: no other process holds the folder. Returns what
// it removed (paths relative to dataDir).
std::vector<std::string> removeLeftovers(const std::filesystem::path& dataDir, bool alone);

}  // namespace orthosim::server
