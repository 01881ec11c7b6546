// Every kind of bad request gets an error naming the problem, and the session keeps working.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "ServerProcess.hpp"
#include "WsTestClient.hpp"

namespace orthosim {
namespace {
using nlohmann::json;
using namespace std::chrono_literals;

// One server and one open session for all the bad requests: each must leave it usable.
class PlanningErrors : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    server_ = new test::ServerProcess();
    ws_ = new test::WsTestClient(server_->port());
    ws_->request({{"type", "open"}, {"case", "phantom-0"}});
    ws_->waitFor("opened", 120s);
  }
  static void TearDownTestSuite() {
    delete ws_;
    delete server_;
  }
  // Sends raw text and returns the error it causes, then checks the session still answers.
  static json errorForText(const std::string& text) {
    ws_->sendText(text);
    const json e = ws_->waitFor("error", 10s);
    EXPECT_EQ(ws_->request({{"type", "describe"}})["type"], "case") << "the session keeps working";
    return e;
  }
  static json errorFor(const json& message) { return errorForText(message.dump()); }

  static test::ServerProcess* server_;
  static test::WsTestClient* ws_;
};
test::ServerProcess* PlanningErrors::server_ = nullptr;
test::WsTestClient* PlanningErrors::ws_ = nullptr;

json poses(const json& maxilla) { return {{"type", "set_poses"}, {"poses", {{"maxilla", maxilla}}}}; }

TEST_F(PlanningErrors, MalformedJson) {
  const json e = errorForText("{\"type\": \"describe\"");
  EXPECT_EQ(e["error"], "malformed_json");
  EXPECT_NE(e["message"].get<std::string>().find("not valid JSON"), std::string::npos);
}

// Bytes the parser stops inside (a multi-byte character, a line separator, an emoji in a literal)
// still get a reply: the message quoting them is sent as valid UTF-8, without the library's tag.
TEST_F(PlanningErrors, EveryMalformedTextGetsAReply) {
  for (const std::string text :
       {"{\"type\":\"list_cases\"\xC3\xA9}", "{\xE2\x80\xA8\"type\":\"list_cases\"}", "{\"x\":tru\xF0\x9F\xA6\xB7}"}) {
    const json e = errorForText(text);
    EXPECT_EQ(e["error"], "malformed_json") << text;
    EXPECT_EQ(e["message"].get<std::string>().find("json.exception"), std::string::npos) << e.dump();
  }
}

TEST_F(PlanningErrors, PathsArePointersAndNumbersAsSent) {
  const json unknown = errorFor(json{{"type", "describe"}, {"/x", 1}});
  EXPECT_EQ(unknown["path"], "/~1x");
  const json pick = errorFor(json{{"type", "pick"}, {"y", 1}});
  EXPECT_EQ(pick["path"], "/x");
  EXPECT_EQ(pick["message"].get<std::string>().rfind("/x: ", 0), 0u) << pick.dump();
  const json job = errorForText(R"({"type":"cancel","job":18446744073709551615})");
  EXPECT_EQ(job["error"], "out_of_range");
  EXPECT_NE(job["message"].get<std::string>().find("18446744073709551615"), std::string::npos) << job.dump();
}

TEST_F(PlanningErrors, NotAnObject) { EXPECT_EQ(errorForText("[1, 2]")["error"], "bad_value"); }

TEST_F(PlanningErrors, MissingType) {
  const json e = errorFor(json{{"case", "phantom-0"}});
  EXPECT_EQ(e["error"], "missing_field");
  EXPECT_EQ(e["path"], "/type");
}

TEST_F(PlanningErrors, UnknownType) {
  const json e = errorFor(json{{"type", "explode"}, {"id", 7}});
  EXPECT_EQ(e["error"], "unknown_type");
  EXPECT_EQ(e["id"], 7) << "errors carry the request's id";
  EXPECT_NE(e["message"].get<std::string>().find("set_poses"), std::string::npos) << "lists the known types";
}

TEST_F(PlanningErrors, UnknownFragment) {
  const json e = errorFor(json{{"type", "set_poses"}, {"poses", {{"jaw", {{"anterior_mm", 1}}}}}});
  EXPECT_EQ(e["error"], "unknown_fragment");
  EXPECT_EQ(e["path"], "/poses/jaw");
  EXPECT_NE(e["message"].get<std::string>().find("maxilla"), std::string::npos) << "names the movable fragments";
}

TEST_F(PlanningErrors, FixedBoneCannotBeMoved) {
  EXPECT_EQ(errorFor(json{{"type", "set_poses"}, {"poses", {{"skull", {{"anterior_mm", 1}}}}}})["error"],
            "unknown_fragment");
}

TEST_F(PlanningErrors, MissingField) {
  EXPECT_EQ(errorFor(json{{"type", "open"}})["path"], "/case");
  EXPECT_EQ(errorFor(json{{"type", "set_poses"}})["path"], "/poses");
  EXPECT_EQ(errorFor(json{{"type", "save_plan"}})["error"], "missing_field");
  EXPECT_EQ(errorFor(json{{"type", "cancel"}})["path"], "/job");
}

TEST_F(PlanningErrors, AbsurdTranslationAndRotation) {
  const json e = errorFor(poses({{"anterior_mm", 500}}));
  EXPECT_EQ(e["error"], "out_of_range");
  EXPECT_EQ(e["path"], "/poses/maxilla/anterior_mm");
  EXPECT_NE(e["message"].get<std::string>().find("500"), std::string::npos);
  EXPECT_EQ(errorFor(poses({{"yaw_deg", -90}}))["path"], "/poses/maxilla/yaw_deg");
}

TEST_F(PlanningErrors, NonFiniteAndNonNumericValues) {
  // JSON has no NaN; a huge exponent is what a client sends for infinity.
  const json inf = errorForText("{\"type\":\"set_poses\",\"poses\":{\"maxilla\":{\"anterior_mm\":1e999}}}");
  EXPECT_EQ(inf["error"], "malformed_json");
  EXPECT_NE(inf["message"].get<std::string>().find("1e999"), std::string::npos) << inf.dump();
  const json e = errorFor(poses({{"anterior_mm", "5"}}));
  EXPECT_EQ(e["error"], "bad_value");
  EXPECT_EQ(e["path"], "/poses/maxilla/anterior_mm");
  EXPECT_EQ(errorFor(poses({{"anterior_mm", nullptr}, {"superior", 1}}))["error"], "unknown_field");
}

TEST_F(PlanningErrors, ARefusedPoseChangesNothing) {
  ws_->request({{"type", "set_poses"}, {"poses", {{"maxilla", {{"anterior_mm", 1}}}}}, {"preview", false}});
  errorFor(
      json{{"type", "set_poses"}, {"poses", {{"maxilla", {{"anterior_mm", 2}}}, {"mandible", {{"anterior_mm", 99}}}}}});
  const json c = ws_->request({{"type", "describe"}});
  for (const json& f : c["fragments"])
    if (f["name"] == "maxilla") EXPECT_EQ(f["pose"]["anterior_mm"], 1.0) << "all or nothing";
}

TEST_F(PlanningErrors, UnknownCaseAndBadNames) {
  EXPECT_EQ(errorFor(json{{"type", "open"}, {"case", "../../etc"}})["error"], "unknown_case");
  for (const char* name : {"../escape", "a/b", "", ".hidden", "with space", "x.json"}) {
    const json e = errorFor(json{{"type", "save_plan"}, {"name", name}});
    EXPECT_EQ(e["error"], "bad_name") << name;
    EXPECT_EQ(e["path"], "/name");
  }
  EXPECT_EQ(errorFor(json{{"type", "load_plan"}, {"name", "never-saved-plan"}})["error"], "not_found");
}

TEST_F(PlanningErrors, OversizedMessageIsSkipped) {
  const std::string big = "{\"type\":\"describe\",\"pad\":\"" + std::string(100 * 1024, 'x') + "\"}";
  const json e = errorForText(big);
  EXPECT_EQ(e["error"], "message_too_large");
  EXPECT_NE(e["message"].get<std::string>().find("65536"), std::string::npos);
}

TEST_F(PlanningErrors, BinaryMessage) {
  ws_->sendBinary(std::string("\x00\x01\x02", 3));
  EXPECT_EQ(ws_->waitFor("error", 10s)["error"], "binary_message");
}

TEST_F(PlanningErrors, BadIdAndUnknownJobAndExport) {
  EXPECT_EQ(errorFor(json{{"type", "describe"}, {"id", {{"a", 1}}}})["path"], "/id");
  EXPECT_EQ(errorFor(json{{"type", "cancel"}, {"job", 123456}})["error"], "unknown_job");
  EXPECT_EQ(errorFor(json{{"type", "export"}, {"format", "exe"}})["path"], "/format");
  EXPECT_EQ(errorFor(json{{"type", "export"}, {"format", "stl"}, {"result", "fine"}})["error"], "no_result");
}

TEST(PlanningErrorsBeforeOpen, PosesNeedAnOpenCase) {
  test::ServerProcess server;
  test::WsTestClient ws(server.port());
  ws.send({{"type", "set_poses"}, {"poses", json::object()}});
  const json e = ws.waitFor("error", 10s);
  EXPECT_EQ(e["error"], "case_not_open");
  EXPECT_NE(e["message"].get<std::string>().find("open"), std::string::npos);
}

}  // namespace
}  // namespace orthosim
