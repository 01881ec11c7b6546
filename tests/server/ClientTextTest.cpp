// What a client is told: no folder of the server's machine, no library tags, pointers as RFC 6901.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "session/MessageReader.hpp"
#include "util/ClientText.hpp"

namespace orthosim::server {
namespace {
using nlohmann::json;

TEST(ClientText, MachinePathsShortenedToTheirLastPart) {
  const std::string data = std::filesystem::temp_directory_path().string() + "/orthosim-data";
  EXPECT_EQ(withoutServerPaths("cannot read '" + data + "/patients/p1/case.json': no such file"),
            "cannot read 'case.json': no such file");
  EXPECT_EQ(withoutServerPaths(data + "/cache/ab.tissue: disk full"), "ab.tissue: disk full");
  EXPECT_EQ(withoutServerPaths("in " + data + "/patients/p1/ (staging)"), "in p1 (staging)");
  EXPECT_EQ(withoutServerPaths("/usr/share/orthosim/cases/demo/skin.stl, line 3"), "skin.stl, line 3");
}

TEST(ClientText, PointersAndWordsWithSlashesStay) {
  EXPECT_EQ(withoutServerPaths("/poses/maxilla/anterior_mm: 500 mm is outside"),
            "/poses/maxilla/anterior_mm: 500 mm is outside");
  EXPECT_EQ(withoutServerPaths("/landmarks/~1x: bad"), "/landmarks/~1x: bad");
  EXPECT_EQ(withoutServerPaths("10 mm/s and a/b"), "10 mm/s and a/b");
  EXPECT_EQ(withoutServerPaths("/tmp alone"), "/tmp alone") << "a bare root names nothing of the patient's";
  EXPECT_EQ(withoutServerPaths(""), "");
}

TEST(ClientText, JsonSyntaxErrorsWithoutTheLibraryTag) {
  try {
    (void)json::parse("{\"type\": tru}");
    FAIL() << "the text is not JSON";
  } catch (const json::exception& e) {
    const std::string m = jsonSyntaxMessage(e);
    EXPECT_EQ(m.find("json.exception"), std::string::npos) << m;
    EXPECT_NE(m.find("column"), std::string::npos) << "says where: " << m;
  }
}

TEST(ClientText, PointersEscapeTheirKeys) {
  EXPECT_EQ(jsonPointer("", "x"), "/x");
  EXPECT_EQ(jsonPointer("/landmarks", "a/b~c"), "/landmarks/a~1b~0c");
  const json message = {{"/x", 1}};
  MessageReader r(message, "");
  try {
    r.rejectUnknown();
    FAIL() << "an unknown field";
  } catch (const ProtocolError& e) {
    EXPECT_EQ(e.code, "unknown_field");
    EXPECT_EQ(e.path, "/~1x");
    EXPECT_EQ(std::string(e.what()).rfind("/~1x: ", 0), 0u) << e.what();
  }
}

TEST(ClientText, NumbersReportedAsSent) {
  const json message = json::parse(R"({"job": 18446744073709551615, "mm": 0.1, "small": -3})");
  MessageReader r(message, "");
  try {
    (void)r.optionalInteger("job", 1, std::numeric_limits<long long>::max());
    FAIL() << "2^64-1 is beyond a job number";
  } catch (const ProtocolError& e) {
    EXPECT_EQ(e.code, "out_of_range");
    EXPECT_NE(std::string(e.what()).find("18446744073709551615 is outside"), std::string::npos) << e.what();
  }
  try {
    (void)r.number("mm", 0, 1, 2, "mm");
    FAIL();
  } catch (const ProtocolError& e) {
    EXPECT_EQ(e.code, "out_of_range");
    EXPECT_NE(std::string(e.what()).find("0.1 mm is outside"), std::string::npos) << e.what();
  }
  try {
    (void)r.optionalInteger("small", 1, 10);
    FAIL();
  } catch (const ProtocolError& e) {
    EXPECT_EQ(e.code, "out_of_range");
    EXPECT_NE(std::string(e.what()).find("-3 is outside"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace orthosim::server
