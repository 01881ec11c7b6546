// The surgeon's name a saved plan records: trimmed, at most 64 characters (not bytes) of valid
// UTF-8 without control characters; anything else is refused with the field named.
#include <gtest/gtest.h>

#include "session/ProtocolError.hpp"
#include "session/UserName.hpp"

namespace orthosim::server {
namespace {

std::string refusal(const std::string& raw) {
  try {
    checkedUserName(raw, "/saved_by");
  } catch (const ProtocolError& e) {
    EXPECT_EQ(e.code, "bad_user_name");
    EXPECT_EQ(e.path, "/saved_by");
    return e.what();
  }
  return "";
}

TEST(UserName, IsTrimmedAndKeptAsGiven) {
  EXPECT_EQ(checkedUserName("  Dr. Zoë Ångström \t", "/saved_by"), "Dr. Zoë Ångström");
  EXPECT_EQ(checkedUserName("", "/saved_by"), "");
  EXPECT_EQ(checkedUserName("<img src=x onerror=alert(1)>", "/saved_by"), "<img src=x onerror=alert(1)>")
      << "markup is text: the page shows it as such";
  std::string wide;
  for (int i = 0; i < 64; ++i) wide += "\xF0\x9F\x98\x80";  // 64 characters of 4 bytes each
  EXPECT_EQ(checkedUserName(wide, "/saved_by"), wide);
}

TEST(UserName, RefusesLongControlAndInvalidText) {
  EXPECT_NE(refusal(std::string(65, 'a')).find("65 characters"), std::string::npos);
  EXPECT_EQ(refusal(std::string(" ") + std::string(64, 'a') + "  "), "") << "64 once trimmed";
  for (const std::string& bad :
       {std::string("a\x01z"), std::string("a\nz"), std::string("a\x7fz"), std::string("a\xC2\x9Bz"),
        std::string("a\xE2\x80\xAEz"), std::string("a\xE2\x81\xA6z")})
    EXPECT_NE(refusal(bad).find("control character"), std::string::npos) << bad;
  for (const std::string& bad : {std::string("a\xFFz"), std::string("a\xC3"), std::string("\xC0\xAF"),
                                 std::string("\xED\xA0\x80"), std::string("\xF4\x90\x80\x80")})
    EXPECT_NE(refusal(bad).find("not valid UTF-8"), std::string::npos) << bad;
}

}  // namespace
}  // namespace orthosim::server
