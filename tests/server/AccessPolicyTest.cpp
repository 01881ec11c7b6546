// The parts of the access checks: Host names and query values.
#include <gtest/gtest.h>

#include "net/AccessPolicy.hpp"
#include "net/BindRule.hpp"

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
  r.set(http::field::authorization, "bearer abc");
  EXPECT_FALSE(policy.checkToken(r, {"/api/health", ""})) << "the scheme is case-insensitive";
  r.set(http::field::authorization, "BEARER   abc");
  EXPECT_FALSE(policy.checkToken(r, {"/api/health", ""}));
  r.set(http::field::authorization, "Basic abc");
  EXPECT_TRUE(policy.checkToken(r, {"/api/health", ""})) << "another scheme";
  r.set(http::field::authorization, "Bearerabc");
  EXPECT_TRUE(policy.checkToken(r, {"/api/health", ""}));
}

// The page's own origin is http:// and the Host: this server has no TLS, so an https origin with
// the same name is another page (a proxy's, allowed by name).
TEST(AccessPolicy, OriginIsThePagesOwn) {
  Request r;
  r.set(http::field::host, "127.0.0.1:8080");
  const AccessPolicy policy(AccessOptions{}, "127.0.0.1");
  r.set(http::field::origin, "http://127.0.0.1:8080");
  EXPECT_FALSE(policy.checkOrigin(r));
  r.set(http::field::origin, "https://127.0.0.1:8080");
  EXPECT_TRUE(policy.checkOrigin(r));
  r.set(http::field::origin, "http://127.0.0.1:8081");
  EXPECT_TRUE(policy.checkOrigin(r));
  AccessOptions proxied;
  proxied.allowedOrigins = {"https://planner.clinic.example"};
  r.set(http::field::origin, "https://planner.clinic.example");
  EXPECT_FALSE(AccessPolicy(proxied, "127.0.0.1").checkOrigin(r));
}

Request withHost(const std::string& host) {
  Request r;
  r.set(http::field::host, host);
  return r;
}

// DNS rebinding: a page of attacker.example whose name now resolves to this server sends
// "Host: attacker.example". Only names of this server pass, however it is bound.
TEST(AccessPolicy, HostNamesOfThisServerOnly) {
  const AccessPolicy loopback(AccessOptions{}, "127.0.0.1");
  EXPECT_FALSE(loopback.checkHost(withHost("localhost:8080")));
  EXPECT_FALSE(loopback.checkHost(withHost("127.0.0.1:8080")));
  EXPECT_FALSE(loopback.checkHost(withHost("[::1]:8080")));
  EXPECT_TRUE(loopback.checkHost(withHost("attacker.example:8080")));

  const AccessPolicy everywhere(AccessOptions{}, "0.0.0.0", {"planner-host"});
  EXPECT_TRUE(everywhere.checkHost(withHost("attacker.example:8080"))) << "bound to 0.0.0.0 is no longer any Host";
  EXPECT_FALSE(everywhere.checkHost(withHost("planner-host:8080"))) << "this machine's name";
  EXPECT_FALSE(everywhere.checkHost(withHost("192.168.1.20:8080"))) << "an address has no name to rebind";
  EXPECT_FALSE(everywhere.checkHost(withHost("[fe80::1]:8080")));
  EXPECT_TRUE(everywhere.checkHost(withHost("192.168.1.20.attacker.example")));

  AccessOptions named;
  named.allowedHosts = {"Planner.Clinic.example"};
  EXPECT_FALSE(AccessPolicy(named, "0.0.0.0").checkHost(withHost("planner.clinic.example")));
  named.allowedHosts = {"*"};
  EXPECT_FALSE(AccessPolicy(named, "0.0.0.0").checkHost(withHost("attacker.example"))) << "the operator said any";
}

TEST(BindRule, OffTheLoopbackATokenOrInsecureIsNeeded) {
  const auto address = [](const char* a) { return boost::asio::ip::make_address(a); };
  EXPECT_FALSE(bindRefusal(address("127.0.0.1"), "", false));
  EXPECT_FALSE(bindRefusal(address("::1"), "", false));
  const std::optional<std::string> open = bindRefusal(address("0.0.0.0"), "", false);
  ASSERT_TRUE(open);
  EXPECT_NE(open->find("every network interface"), std::string::npos) << *open;
  EXPECT_NE(open->find("--token"), std::string::npos) << *open;
  EXPECT_NE(open->find("--insecure"), std::string::npos) << *open;
  EXPECT_TRUE(bindRefusal(address("192.168.1.20"), "", false));
  EXPECT_TRUE(bindRefusal(address("::"), "", false));
  EXPECT_FALSE(bindRefusal(address("0.0.0.0"), "s3cret", false));
  EXPECT_FALSE(bindRefusal(address("0.0.0.0"), "", true));
}

}  // namespace
}  // namespace orthosim::net
