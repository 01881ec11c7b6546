// Saved plans name the osteotomy set they were made on: loading one on a case
// cut differently is refused with both sets named, and plans saved before that still load.
#include <gtest/gtest.h>

#include "session/ProtocolError.hpp"
#include "session/SavedPlan.hpp"

namespace orthosim::server {
namespace {
using nlohmann::json;

std::vector<OsteotomySpec> cuts(bool withBsso) {
  std::vector<OsteotomySpec> c(1);
  c[0].kind = "le_fort_1";
  c[0].bone = "skull";
  if (withBsso) {
    c.emplace_back();
    c[1].kind = "bsso";
    c[1].bone = "mandible";
    c[1].offset = 14;
  }
  return c;
}

std::map<std::string, AnatomicalPose> noPoses(MessageReader) { return {}; }

TEST(SavedPlan, NamesItsOsteotomiesAndIsRefusedOnOthers) {
  const json both = osteotomySetJson(cuts(true)), maxillaOnly = osteotomySetJson(cuts(false));
  ASSERT_EQ(both.size(), 2u);
  EXPECT_EQ(both[1]["kind"], "bsso");
  EXPECT_EQ(both[1]["offset_mm"], 14.0);
  const json plan = savedPlanJson("patient-7", "setback", json::object(), {}, both);
  EXPECT_EQ(plan["cuts"], both);
  EXPECT_NO_THROW(readSavedPlan(plan, "setback", noPoses, both));
  try {
    readSavedPlan(plan, "setback", noPoses, maxillaOnly);
    FAIL() << "loaded on another osteotomy set";
  } catch (const ProtocolError& e) {
    EXPECT_EQ(e.code, "other_osteotomies");
    const std::string m = e.what();
    EXPECT_NE(m.find("'setback'"), std::string::npos) << m;
    EXPECT_NE(m.find("le_fort_1 (skull), bsso (mandible)"), std::string::npos) << m;
    EXPECT_NE(m.find("the case now has le_fort_1 (skull)"), std::string::npos) << m;
  }
  // A moved cut is another set too.
  std::vector<OsteotomySpec> moved = cuts(true);
  moved[1].offset = 10;
  EXPECT_THROW(readSavedPlan(plan, "setback", noPoses, osteotomySetJson(moved)), ProtocolError);
  // Saved before plans named their cuts: loads on any set.
  json old = plan;
  old.erase("cuts");
  EXPECT_NO_THROW(readSavedPlan(old, "setback", noPoses, maxillaOnly));
}

}  // namespace
}  // namespace orthosim::server
