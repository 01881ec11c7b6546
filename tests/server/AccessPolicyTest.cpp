// The parts of the access checks: Host names and query values.
#include <gtest/gtest.h>

#include "net/AccessPolicy.hpp"

namespace orthosim::net {
namespace {

TEST(AccessPolicy, HostName) {
  EXPECT_EQ(hostName("127.0.0.1:8080"), "127.0.0.1");
  EXPECT_EQ(hostName("LocalHost"), "localhost");
  EXPECT_EQ(hostName("[::1]:80"), "[::1]");
  EXPECT_EQ(hostName(""), "");
}

TEST(AccessPolicy, QueryValue) {
  EXPECT_EQ(queryValue("a=1&token=x%2By&b", "token"), "x+y");
  EXPECT_EQ(queryValue("token=", "token"), "");
  EXPECT_FALSE(queryValue("tokens=1&atoken=2", "token"));
  EXPECT_EQ(queryValue("token=%zz", "token"), "%zz");
}

TEST(AccessPolicy, TokenComparison) {
  AccessOptions o;
  o.token = "abc";
  const AccessPolicy policy(o, "127.0.0.1");
  Request r;
  r.set(http::field::authorization, "Bearer abc");
  EXPECT_FALSE(policy.checkToken(r, {"/api/health", ""}));
  r.set(http::field::authorization, "Bearer abcd");
  EXPECT_TRUE(policy.checkToken(r, {"/api/health", ""}));
  r.set(http::field::authorization, "Bearer ab");
  EXPECT_TRUE(policy.checkToken(r, {"/api/health", ""}));
  EXPECT_FALSE(policy.checkToken(Request{}, {"/ws", "token=abc"}));
}

}  // namespace
}  // namespace orthosim::net
