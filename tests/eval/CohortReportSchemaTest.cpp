// The committed accuracy report (web/cohort/cohort.json, shown by the page and checked by
// web.AccuracyReport) is a snapshot of an `orthosim bench cohort` run, too slow to redo in CI: its
// schema_version must be the one the bench writes now, and the one the page's reader expects, so
// that a change of the format without a fresh report is noticed here.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>

#include "eval/CohortJson.hpp"

namespace orthosim {
namespace {

std::string readSource(const char* path) {
  std::ifstream in(std::string(ORTHOSIM_SOURCE_DIR) + "/" + path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(CohortReportSchema, TheCommittedReportIsInTheBenchsCurrentFormat) {
  const nlohmann::json report = nlohmann::json::parse(readSource("web/cohort/cohort.json"));
  ASSERT_TRUE(report.contains("schema_version")) << "web/cohort/cohort.json predates the schema version: refresh it";
  EXPECT_EQ(report["schema_version"].get<int>(), kCohortReportSchemaVersion)
      << "web/cohort/cohort.json is in another format than `orthosim bench cohort` writes: refresh it (README)";
}

TEST(CohortReportSchema, ThePageReadsTheBenchsCurrentFormat) {
  const std::string page = readSource("web/report.js");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(page, m, std::regex(R"(const REPORT_SCHEMA_VERSION = (\d+);)"))) << "web/report.js";
  EXPECT_EQ(std::stoi(m[1]), kCohortReportSchemaVersion)
      << "web/report.js reads another report format than the bench writes";
}

}  // namespace
}  // namespace orthosim
