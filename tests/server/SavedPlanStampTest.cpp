// Saved plans say who saved them and when, and no session overwrites a plan unasked: save_plan
// records saved_by and saved_at, list_plans lists them beside the names, a save over a saved name
// is refused with plan_exists (naming who and when) unless it says "replace": true, a user name
// that is too long or holds a control character is refused with its field named, and a plan file
// written before plans were stamped still lists and loads.
#include <gtest/gtest.h>
#include <utime.h>

#include <ctime>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>

#include "ServerProcess.hpp"
#include "WsTestClient.hpp"

namespace orthosim {
namespace {
using nlohmann::json;
using namespace std::chrono_literals;
namespace fs = std::filesystem;

void openPhantom(test::WsTestClient& ws) {
  ASSERT_EQ(ws.request({{"type", "open"}, {"case", "phantom-0"}})["type"], "opening");
  ws.waitFor("opened", 120s);
}

std::string uniqueName(const std::string& stem) {
  std::random_device r;
  return stem + "-" + std::to_string(r() % 1000000);
}

fs::path planFile(const std::string& name) {
  return fs::path(test::testDataDir()) / "plans" / "phantom-0" / (name + ".json");
}

// The details entry list_plans gives for `name` (null when it lists none).
json detailsOf(test::WsTestClient& ws, const std::string& name) {
  const json plans = ws.request({{"type", "list_plans"}});
  EXPECT_EQ(plans["type"], "plans") << plans.dump();
  const auto& names = plans["plans"];
  EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << "the names list is kept: " << plans.dump();
  for (const json& d : plans["details"])
    if (d["name"] == name) return d;
  return nullptr;
}

std::time_t parseUtc(const std::string& iso) {
  std::tm t{};
  if (!strptime(iso.c_str(), "%Y-%m-%dT%H:%M:%SZ", &t)) return -1;
  return timegm(&t);
}

TEST(SavedPlanStamp, SavedByAndSavedAtAreRecordedListedAndNeverOverwrittenUnasked) {
  test::ServerProcess server;
  const std::string name = uniqueName("stamped");
  test::WsTestClient a(server.port()), b(server.port());
  openPhantom(a);
  openPhantom(b);
  a.request({{"type", "set_poses"}, {"poses", {{"maxilla", {{"anterior_mm", 2}}}}}, {"preview", false}});
  const std::time_t before = std::time(nullptr);
  const json saved = a.request({{"type", "save_plan"}, {"name", name}, {"saved_by", "  Dr. Zoë Ångström  "}});
  const std::time_t after = std::time(nullptr);
  ASSERT_EQ(saved["type"], "saved") << saved.dump();
  EXPECT_EQ(saved["saved_by"], "Dr. Zoë Ångström") << "stored trimmed";
  const std::string at = saved["saved_at"];
  ASSERT_EQ(at.size(), 20u) << at;
  EXPECT_GE(parseUtc(at), before - 1) << at;
  EXPECT_LE(parseUtc(at), after + 1) << at;
  std::ifstream in(planFile(name));
  const json file = json::parse(in);
  EXPECT_EQ(file["saved_by"], "Dr. Zoë Ångström");
  EXPECT_EQ(file["saved_at"], at);

  // Another session sees who saved it and when.
  const json listed = detailsOf(b, name);
  ASSERT_TRUE(listed.is_object());
  EXPECT_EQ(listed["saved_by"], "Dr. Zoë Ångström");
  EXPECT_EQ(listed["saved_at"], at);

  // Its save over the name is refused, naming who saved it and when; the plan stays.
  b.request({{"type", "set_poses"}, {"poses", {{"maxilla", {{"anterior_mm", -3}}}}}, {"preview", false}});
  const json refused = b.request({{"type", "save_plan"}, {"name", name}, {"saved_by", "Dr. B"}});
  EXPECT_EQ(refused["type"], "error") << refused.dump();
  EXPECT_EQ(refused["error"], "plan_exists");
  EXPECT_EQ(refused["path"], "/name");
  const std::string message = refused["message"];
  EXPECT_NE(message.find("Dr. Zoë Ångström"), std::string::npos) << message;
  EXPECT_NE(message.find(at), std::string::npos) << message;
  EXPECT_EQ(b.request({{"type", "load_plan"}, {"name", name}, {"preview", false}})["poses"]["maxilla"]["anterior_mm"],
            2.0)
      << "the first plan is still saved";

  // With "replace": true it is replaced, and the new author is listed.
  b.request({{"type", "set_poses"}, {"poses", {{"maxilla", {{"anterior_mm", -3}}}}}, {"preview", false}});
  const json replaced = b.request({{"type", "save_plan"}, {"name", name}, {"saved_by", "Dr. B"}, {"replace", true}});
  ASSERT_EQ(replaced["type"], "saved") << replaced.dump();
  EXPECT_EQ(replaced["saved_by"], "Dr. B");
  EXPECT_EQ(detailsOf(a, name)["saved_by"], "Dr. B");
  EXPECT_EQ(a.request({{"type", "load_plan"}, {"name", name}, {"preview", false}})["poses"]["maxilla"]["anterior_mm"],
            -3.0);

  // No name given: saved with an empty saved_by.
  const std::string anonymous = uniqueName("unnamed");
  const json unnamed = a.request({{"type", "save_plan"}, {"name", anonymous}});
  ASSERT_EQ(unnamed["type"], "saved") << unnamed.dump();
  EXPECT_EQ(unnamed["saved_by"], "");
  EXPECT_EQ(detailsOf(b, anonymous)["saved_by"], "");
  fs::remove(planFile(name));
  fs::remove(planFile(anonymous));
}

TEST(SavedPlanStamp, ABadUserNameIsRefusedWithItsField) {
  test::ServerProcess server;
  test::WsTestClient ws(server.port());
  openPhantom(ws);
  const std::string name = uniqueName("bad-user");
  const std::string tooLong(65, 'a');
  for (const std::string& user : {tooLong, std::string("Dr.\x01Who"), std::string("line\nbreak"),
                                  std::string("bidi \xE2\x80\xAE override"), std::string("Dr. \xC2\x85")}) {
    const json e = ws.request({{"type", "save_plan"}, {"name", name}, {"saved_by", user}});
    EXPECT_EQ(e["type"], "error") << e.dump();
    EXPECT_EQ(e["error"], "bad_user_name") << e.dump();
    EXPECT_EQ(e["path"], "/saved_by") << e.dump();
  }
  EXPECT_NE(
      ws.request({{"type", "save_plan"}, {"name", name}, {"saved_by", tooLong}})["message"].get<std::string>().find(
          "64"),
      std::string::npos)
      << "the limit is named";
  // 64 characters of several bytes each are within the limit; a number is not a name.
  std::string wide;
  for (int i = 0; i < 64; ++i) wide += "é";
  const json ok = ws.request({{"type", "save_plan"}, {"name", name}, {"saved_by", wide}});
  EXPECT_EQ(ok["type"], "saved") << ok.dump();
  EXPECT_EQ(ws.request({{"type", "save_plan"}, {"name", name}, {"saved_by", 7}, {"replace", true}})["path"],
            "/saved_by");
  EXPECT_FALSE(fs::exists(planFile(name + "x")));
  fs::remove(planFile(name));
}

TEST(SavedPlanStamp, APlanSavedBeforeStampsListsAndLoads) {
  test::ServerProcess server;
  test::WsTestClient ws(server.port());
  openPhantom(ws);
  const std::string name = uniqueName("old-plan");
  ws.request({{"type", "set_poses"}, {"poses", {{"mandible", {{"anterior_mm", -1.5}}}}}, {"preview", false}});
  ASSERT_EQ(ws.request({{"type", "save_plan"}, {"name", name}, {"saved_by", "Dr. New"}})["type"], "saved");
  // The same file as a server before stamps wrote it, last written at a known time.
  json file;
  {
    std::ifstream in(planFile(name));
    file = json::parse(in);
  }
  file.erase("saved_by");
  file.erase("saved_at");
  std::ofstream(planFile(name)) << file.dump(2);
  const std::time_t written = parseUtc("2023-03-04T05:06:07Z");
  const utimbuf times{written, written};
  ASSERT_EQ(::utime(planFile(name).c_str(), &times), 0);

  const json listed = detailsOf(ws, name);
  ASSERT_TRUE(listed.is_object());
  EXPECT_EQ(listed["saved_by"], "");
  EXPECT_EQ(listed["saved_at"], "2023-03-04T05:06:07Z") << "the file's time";
  const json loaded = ws.request({{"type", "load_plan"}, {"name", name}, {"preview", false}});
  ASSERT_EQ(loaded["type"], "loaded") << loaded.dump();
  EXPECT_EQ(loaded["poses"]["mandible"]["anterior_mm"], -1.5);
  // Replacing it names that it was saved before names were kept.
  const json refused = ws.request({{"type", "save_plan"}, {"name", name}});
  EXPECT_EQ(refused["error"], "plan_exists") << refused.dump();
  EXPECT_NE(refused["message"].get<std::string>().find("2023-03-04T05:06:07Z"), std::string::npos) << refused.dump();
  fs::remove(planFile(name));
}

}  // namespace
}  // namespace orthosim
