// `orthosim bench MODE`: the benchmarks are subcommands with their own options; a mode must be
// named, and the old mode flags are refused rather than silently timing the blocks.
#include <gtest/gtest.h>

#include <string>

#include "RunCli.hpp"

namespace orthosim {
namespace {

using test::CliRun;
using test::runCli;

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
