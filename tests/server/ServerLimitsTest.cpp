// Requests over the size limits or malformed get a clear error, and the server keeps serving.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "HttpTestClient.hpp"
#include "ServerProcess.hpp"

namespace http = boost::beast::http;

namespace orthosim {
namespace {

TEST(ServerLimits, OversizedBodyIs413) {
  test::ServerProcess server;
  // The declared length alone exceeds the 64 KiB limit: refused before any body is read.
  const auto replies = test::httpRaw(
      server.port(), "POST /api/health HTTP/1.1\r\nHost: x\r\nContent-Length: 100000\r\n\r\n" + std::string(1000, 'x'));
  ASSERT_EQ(replies.size(), 1u);
  EXPECT_EQ(replies[0].result(), http::status::payload_too_large);
  EXPECT_EQ(nlohmann::json::parse(replies[0].body())["error"], "body_too_large");
  EXPECT_FALSE(replies[0].keep_alive());

  // A chunked body that grows past the limit is cut off the same way, even sent in full.
  std::string chunked = "POST /api/health HTTP/1.1\r\nHost: x\r\nTransfer-Encoding: chunked\r\n\r\n";
  for (int i = 0; i < 20; ++i) chunked += "1000\r\n" + std::string(0x1000, 'y') + "\r\n";
  chunked += "0\r\n\r\n";
  const auto chunkedReplies = test::httpRaw(server.port(), chunked);
  ASSERT_EQ(chunkedReplies.size(), 1u);
  EXPECT_EQ(chunkedReplies[0].result(), http::status::payload_too_large);

  EXPECT_EQ(test::httpGet(server.port(), "/api/health").result(), http::status::ok);
}

TEST(ServerLimits, OversizedHeadersAre431) {
  test::ServerProcess server;
  const auto replies = test::httpRaw(
      server.port(), "GET /api/health HTTP/1.1\r\nHost: x\r\nX-Padding: " + std::string(100 * 1024, 'p') + "\r\n\r\n");
  ASSERT_EQ(replies.size(), 1u);
  EXPECT_EQ(replies[0].result(), http::status::request_header_fields_too_large);
  EXPECT_EQ(nlohmann::json::parse(replies[0].body())["error"], "header_too_large");
  EXPECT_EQ(test::httpGet(server.port(), "/api/health").result(), http::status::ok);
}

TEST(ServerLimits, MalformedRequestIs400) {
  test::ServerProcess server;
  const auto replies = test::httpRaw(server.port(), "GET /api/health NOT-HTTP\r\n\r\n");
  ASSERT_EQ(replies.size(), 1u);
  EXPECT_EQ(replies[0].result(), http::status::bad_request);
  EXPECT_EQ(nlohmann::json::parse(replies[0].body())["error"], "bad_request");
  EXPECT_EQ(test::httpGet(server.port(), "/api/health").result(), http::status::ok);
}

}  // namespace
}  // namespace orthosim
