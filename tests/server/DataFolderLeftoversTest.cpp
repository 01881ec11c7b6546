// What interrupted writers leave in the data folder (session/DataFolderLeftovers): a tissue-cache
// entry and a case edit cut off by a full disk stayed there for good. A starting server now removes
// every temporary file whose writer has ended, and none that a live process is writing, though its
// name looks the same; another host's are removed only by a process that has the folder alone.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "ServerProcess.hpp"
#include "session/DataFolderLeftovers.hpp"
#include "system/TemporaryName.hpp"

namespace orthosim {
namespace {
namespace fs = std::filesystem;

// A pid no process has: a child that has ended and been waited for.
pid_t endedPid() {
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ::waitpid(child, nullptr, 0);
  return child;
}

std::string suffixOf(const std::string& host, long pid) {
  return host + "-" + std::to_string(pid) + "-0123456789abcdef";
}

void plant(const fs::path& file) {
  fs::create_directories(file.parent_path());
  std::ofstream(file) << "";  // what a full disk leaves: 0 bytes
}

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::path(test::testDataDir()) / "leftovers" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(DataFolderLeftovers, AStartingServerRemovesWhatEndedWritersLeftAndNothingALiveOneWrites) {
  const fs::path data = scratch("server-start");
  const std::string ended = suffixOf(temporaryHost(), endedPid());
  const std::string live = suffixOf(temporaryHost(), ::getpid());  // this test: running
  const std::vector<fs::path> gone = {
      data / "cache" / ("3f9c0e1d.tissue.tmp" + ended),
      data / "patients" / "jane" / (".case.json.editing-" + ended),
      data / "plans" / "phantom-0" / ("setback.json.tmp" + ended),
      data / "jobs" / ("7.nodes.part-" + ended),
      data / "jobs" / ("8.band.json.tmp" + ended),
      data / "cases" / "phantom-0" / ("case.json.writing-" + ended),
      data / "imports" / ("body-" + ended),
  };
  const std::vector<fs::path> kept = {
      data / "cache" / ("5a5a5a5a.tissue.tmp" + live),
      data / "imports" / ("body-" + live),  // an upload being received
      data / "patients" / "jane" / (".case.json.editing-" + live),
      data / "plans" / "phantom-0" / ("advance.json.tmp" + live),
      data / "plans" / "phantom-0" / "setback.json",  // files of the folder's own are never touched
      data / "cache" / "3f9c0e1d.tissue",
      data / "patients" / "jane" / "case.json",
  };
  for (const fs::path& f : gone) plant(f);
  for (const fs::path& f : kept) plant(f);
  const fs::path log = data.parent_path() / "server-start-stderr.txt";
  test::ServerProcess server({"--data", data.string(), "--no-warm-up"}, log.string());
  for (const fs::path& f : gone) EXPECT_FALSE(fs::exists(f)) << f;
  for (const fs::path& f : kept) EXPECT_TRUE(fs::exists(f)) << f;
}

// With the folder shared (replicas, workers), another host's temporary files may be in the writing:
// they stay; this host's ended writers' go all the same.
TEST(DataFolderLeftovers, ASharedFolderKeepsOtherHostsTemporaryFiles) {
  const fs::path data = scratch("shared");
  const fs::path otherHost = data / "cache" / ("3f9c0e1d.tissue.tmp" + suffixOf("node-b", 7));
  const fs::path oldName = data / "plans" / "phantom-0" / "setback.json.tmp4242-0";  // names no writer
  const fs::path ended = data / "cache" / ("5a5a5a5a.tissue.tmp" + suffixOf(temporaryHost(), endedPid()));
  for (const fs::path& f : {otherHost, oldName, ended}) plant(f);

  const std::vector<std::string> shared = server::removeLeftovers(data, /*alone=*/false);
  EXPECT_EQ(shared, std::vector<std::string>{fs::relative(ended, data).string()});
  EXPECT_TRUE(fs::exists(otherHost));
  EXPECT_TRUE(fs::exists(oldName));

  const std::vector<std::string> alone = server::removeLeftovers(data, /*alone=*/true);
  EXPECT_EQ(alone.size(), 2u);
  EXPECT_FALSE(fs::exists(otherHost));
  EXPECT_FALSE(fs::exists(oldName));
}

}  // namespace
}  // namespace orthosim
