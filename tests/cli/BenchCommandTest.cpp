// `orthosim bench MODE`: the benchmarks are subcommands with their own options; a mode must be
// named, and the old mode flags are refused rather than silently timing the blocks.
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <string>

namespace orthosim {
namespace {

struct CliRun {
  int status;
  std::string out;
};

CliRun runCli(const std::string& args) {
  const std::string cmd = std::string(ORTHOSIM_CLI) + " " + args + " 2>&1";
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(cmd.c_str(), "r"), pclose);
  std::string out;
  char buf[4096];
  for (size_t n; (n = fread(buf, 1, sizeof buf, pipe.get())) > 0;) out.append(buf, n);
  const int status = pclose(pipe.release());
  return {WEXITSTATUS(status), out};
}

TEST(BenchCommand, ListsItsModesAsSubcommands) {
  const CliRun r = runCli("bench --help");
  EXPECT_EQ(r.status, 0) << r.out;
  for (const char* mode : {"blocks", "phantom", "case", "latency", "render", "cohort"})
    EXPECT_NE(r.out.find(std::string("\n  ") + mode), std::string::npos) << mode << " in\n" << r.out;
}

TEST(BenchCommand, NeedsAModeAndRefusesTheOldFlags) {
  EXPECT_EQ(runCli("bench").status, 1);
  EXPECT_EQ(runCli("bench --cohort --patients 1").status, 1);
  EXPECT_EQ(runCli("bench cohort --tets 2000").status, 1) << "blocks' option on the cohort";
  EXPECT_EQ(runCli("bench case").status, 1) << "case needs its file";
}

}  // namespace
}  // namespace orthosim
