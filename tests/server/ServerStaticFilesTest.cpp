// `orthosim serve` serves the web folder, with the right Content-Type, and nothing outside it.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "HttpTestClient.hpp"
#include "ServerProcess.hpp"
#include "TempWebFolder.hpp"

namespace http = boost::beast::http;

namespace orthosim {
namespace {

using test::httpGet;

TEST(ServerStaticFiles, ServesTheProjectIndexPage) {
  test::ServerProcess server;  // default --web: the project's web/ folder
  for (const char* target : {"/", "/index.html"}) {
    const test::HttpReply reply = httpGet(server.port(), target);
    ASSERT_EQ(reply.result(), http::status::ok) << target;
    EXPECT_EQ(reply[http::field::content_type], "text/html; charset=utf-8");
    EXPECT_NE(reply.body().find("orthosim"), std::string::npos);
    EXPECT_NE(reply.body().find("app.js"), std::string::npos);
  }
  const test::HttpReply script = httpGet(server.port(), "/app.js");
  ASSERT_EQ(script.result(), http::status::ok);
  EXPECT_NE(script.body().find("/ws"), std::string::npos) << "the page talks to the WebSocket API";
  EXPECT_EQ(httpGet(server.port(), "/style.css").result(), http::status::ok);
}

TEST(ServerStaticFiles, ContentTypesFollowTheExtension) {
  const test::TempWebFolder folder("static_types");
  const std::string png("\x89PNG\r\n\x1a\n\0\0", 10);  // binary, with NUL bytes
  folder.write("index.html", "<!DOCTYPE html>");
  folder.write("js/app.js", "console.log(1);");
  folder.write("css/page.css", "body{}");
  folder.write("img/skin.png", png);
  folder.write("img/skin.jpg", "\xff\xd8\xff");
  folder.write("data/case.json", "{}");
  test::ServerProcess server({"--web", folder.web.string()});
  const std::pair<const char*, const char*> expected[] = {{"/index.html", "text/html; charset=utf-8"},
                                                          {"/js/app.js", "text/javascript; charset=utf-8"},
                                                          {"/css/page.css", "text/css; charset=utf-8"},
                                                          {"/img/skin.png", "image/png"},
                                                          {"/img/skin.jpg", "image/jpeg"},
                                                          {"/data/case.json", "application/json"}};
  for (const auto& [target, type] : expected) {
    const test::HttpReply reply = httpGet(server.port(), target);
    EXPECT_EQ(reply.result(), http::status::ok) << target;
    EXPECT_EQ(reply[http::field::content_type], type) << target;
  }
  EXPECT_EQ(httpGet(server.port(), "/img/skin.png").body(), png);  // byte for byte
  const test::HttpReply head = test::httpRequest(server.port(), http::verb::head, "/img/skin.png");
  EXPECT_EQ(head.result(), http::status::ok);
  EXPECT_EQ(head[http::field::content_length], "10");
}

TEST(ServerStaticFiles, TraversalIsRefused) {
  const test::TempWebFolder folder("static_traversal");
  folder.write("index.html", "page");
  std::filesystem::create_symlink(folder.secret, folder.web / "link.txt");
  test::ServerProcess server({"--web", folder.web.string()});
  const std::string secretPath = folder.secret.string();
  for (const std::string& target :
       {std::string("/../secret.txt"), std::string("/%2e%2e/secret.txt"), std::string("/%2E%2E%2Fsecret.txt"),
        std::string("/..%2fsecret.txt"), std::string("/x/../../secret.txt"), std::string("/..\\secret.txt"),
        "/" + secretPath, "//" + secretPath, std::string("/link.txt"), std::string("/%00"), std::string("/etc/passwd"),
        "http://127.0.0.1" + secretPath}) {
    const test::HttpReply reply = httpGet(server.port(), target);
    EXPECT_TRUE(reply.result() == http::status::not_found || reply.result() == http::status::bad_request)
        << target << " -> " << reply.result_int();
    EXPECT_EQ(reply.body().find("SECRET"), std::string::npos) << target;
    EXPECT_EQ(reply[http::field::content_type], "application/json") << target;
  }
  EXPECT_EQ(httpGet(server.port(), "/../secret.txt").result(), http::status::bad_request);
  EXPECT_EQ(httpGet(server.port(), "/link.txt").result(), http::status::not_found);
  EXPECT_EQ(httpGet(server.port(), "/").body(), "page");  // and the server still serves its page
}

TEST(ServerStaticFiles, MissingWebFolderStopsTheServerFromStarting) {
  const std::string command =
      std::string(ORTHOSIM_CLI) + " serve --port 0 --web /nonexistent/orthosim-web >/dev/null 2>&1";
  EXPECT_EQ(WEXITSTATUS(std::system(command.c_str())), 1);
}

}  // namespace
}  // namespace orthosim
