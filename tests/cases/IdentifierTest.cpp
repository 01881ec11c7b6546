// Case and plan names that may become file names (server/cases/Identifier).
#include <gtest/gtest.h>

#include "cases/Identifier.hpp"

namespace orthosim::server {
namespace {

TEST(Identifier, OnlySafeNames) {
  for (const char* ok : {"a", "plan-1", "Case_07", "0abc"}) EXPECT_TRUE(isIdentifier(ok)) << ok;
  for (const char* bad : {"", "-a", "_a", "a.b", "a/b", "..", "a b", "é"}) EXPECT_FALSE(isIdentifier(bad)) << bad;
  EXPECT_FALSE(isIdentifier(std::string(65, 'a')));
  EXPECT_TRUE(isIdentifier(std::string(64, 'a')));
}

}  // namespace
}  // namespace orthosim::server
