// The HTTP API of `orthosim serve`, over a real socket to the real executable.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "HttpTestClient.hpp"
#include "ServerProcess.hpp"

namespace http = boost::beast::http;

namespace orthosim {
namespace {

using test::httpGet;

TEST(ServerApi, HealthIsOk) {
  test::ServerProcess server;
  EXPECT_EQ(server.listeningLine(), "listening on http://127.0.0.1:" + std::to_string(server.port()) + "\n");
  const test::HttpReply reply = httpGet(server.port(), "/api/health");
  EXPECT_EQ(reply.result(), http::status::ok);
  EXPECT_EQ(reply[http::field::content_type], "application/json");
  const nlohmann::json health = nlohmann::json::parse(reply.body());
  EXPECT_EQ(health["status"], "ok");
  EXPECT_FALSE(health["version"].get<std::string>().empty());
  EXPECT_EQ(httpGet(server.port(), "/api/health?probe=1").result(), http::status::ok);  // query ignored
}

TEST(ServerApi, CasesListsThePhantomVariantsAndTheRealFace) {
  test::ServerProcess server;
  const test::HttpReply reply = httpGet(server.port(), "/api/cases");
  ASSERT_EQ(reply.result(), http::status::ok);
  const nlohmann::json cases = nlohmann::json::parse(reply.body())["cases"];
  ASSERT_EQ(cases.size(), 6u);
  EXPECT_EQ(cases[5]["id"], "artisynth-face");
  EXPECT_EQ(cases[5]["source"], "artisynth");
  const char* names[] = {"class-I", "class-II", "class-III", "asymmetric", "long-face"};
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(cases[i]["id"], "phantom-" + std::to_string(i));
    EXPECT_EQ(cases[i]["name"], names[i]);
    EXPECT_EQ(cases[i]["source"], "phantom");
    EXPECT_EQ(cases[i]["variant"], i);
    EXPECT_FALSE(cases[i]["description"].get<std::string>().empty());
  }
}

TEST(ServerApi, UnknownRouteIs404WithAJsonErrorNamingThePath) {
  test::ServerProcess server;
  const test::HttpReply reply = httpGet(server.port(), "/api/nope?x=1");
  EXPECT_EQ(reply.result(), http::status::not_found);
  EXPECT_EQ(reply[http::field::content_type], "application/json");
  const nlohmann::json error = nlohmann::json::parse(reply.body());
  EXPECT_EQ(error["error"], "not_found");
  EXPECT_EQ(error["path"], "/api/nope");
  EXPECT_NE(error["message"].get<std::string>().find("/api/nope"), std::string::npos);

  const test::HttpReply page = httpGet(server.port(), "/no/such/page.html");  // outside /api too
  EXPECT_EQ(page.result(), http::status::not_found);
  EXPECT_EQ(nlohmann::json::parse(page.body())["path"], "/no/such/page.html");
}

TEST(ServerApi, OnlyGetAndHeadAreAllowed) {
  test::ServerProcess server;
  const test::HttpReply post = test::httpRequest(server.port(), http::verb::post, "/api/health");
  EXPECT_EQ(post.result(), http::status::method_not_allowed);
  EXPECT_EQ(post[http::field::allow], "GET, HEAD");
  EXPECT_EQ(nlohmann::json::parse(post.body())["error"], "method_not_allowed");

  const test::HttpReply head = test::httpRequest(server.port(), http::verb::head, "/api/health");
  EXPECT_EQ(head.result(), http::status::ok);
  EXPECT_TRUE(head.body().empty());
  EXPECT_EQ(head[http::field::content_length], std::to_string(httpGet(server.port(), "/api/health").body().size()));
}

TEST(ServerApi, KeepAliveServesSeveralRequestsOnOneConnection) {
  test::ServerProcess server;
  const std::string request = "GET /api/health HTTP/1.1\r\nHost: 127.0.0.1\r\n\r\n";
  const std::string last = "GET /api/cases HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n";
  // Three pipelined requests on one connection, answered in order; the last one closes it.
  const std::vector<test::HttpReply> replies = test::httpRaw(server.port(), request + request + last);
  ASSERT_EQ(replies.size(), 3u);
  EXPECT_TRUE(replies[0].keep_alive());
  EXPECT_EQ(nlohmann::json::parse(replies[1].body())["status"], "ok");
  EXPECT_EQ(nlohmann::json::parse(replies[2].body())["cases"].size(), 6u);
}

}  // namespace
}  // namespace orthosim
