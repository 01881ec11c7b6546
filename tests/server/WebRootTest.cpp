// WebRoot maps request paths to files inside the web folder and nowhere else.
#include "net/WebRoot.hpp"

#include <gtest/gtest.h>

#include "TempWebFolder.hpp"
#include "net/MimeType.hpp"
#include "net/RequestTarget.hpp"

namespace fs = std::filesystem;

namespace orthosim {
namespace {

using net::WebRoot;

TEST(ServerWebRoot, FindsFilesAndIndex) {
  const test::TempWebFolder folder("webroot_find");
  folder.write("index.html", "<p>hi</p>");
  folder.write("js/app.js", "1;");
  folder.write("sub/index.html", "sub");
  const WebRoot root(folder.web);
  EXPECT_EQ(root.find("/").outcome, WebRoot::Outcome::Found);
  EXPECT_EQ(root.find("/").file, fs::canonical(folder.web / "index.html"));
  EXPECT_EQ(root.find("/js/app.js").file, fs::canonical(folder.web / "js/app.js"));
  EXPECT_EQ(root.find("/sub").file, fs::canonical(folder.web / "sub/index.html"));  // folder: its index
  EXPECT_EQ(root.find("//js//./app.js").outcome, WebRoot::Outcome::Found);          // empty and "." segments
  EXPECT_EQ(root.find("/js/").outcome, WebRoot::Outcome::NotFound);                 // folder without index
  EXPECT_EQ(root.find("/missing.css").outcome, WebRoot::Outcome::NotFound);
}

TEST(ServerWebRoot, RefusesEverythingOutside) {
  const test::TempWebFolder folder("webroot_outside");
  folder.write("index.html", "x");
  folder.write(".hidden", "x");
  fs::create_symlink(folder.secret, folder.web / "link.txt");
  fs::create_symlink(folder.base, folder.web / "up");
  const WebRoot root(folder.web);
  EXPECT_EQ(root.find("/../secret.txt").outcome, WebRoot::Outcome::Refused);
  EXPECT_EQ(root.find("/js/../../secret.txt").outcome, WebRoot::Outcome::Refused);
  EXPECT_EQ(root.find("/..").outcome, WebRoot::Outcome::Refused);
  EXPECT_EQ(root.find("/..\\secret.txt").outcome, WebRoot::Outcome::Refused);
  EXPECT_EQ(root.find("relative").outcome, WebRoot::Outcome::Refused);
  EXPECT_EQ(root.find(folder.secret.string()).outcome, WebRoot::Outcome::NotFound);  // absolute: taken as inside web/
  EXPECT_EQ(root.find("/link.txt").outcome, WebRoot::Outcome::NotFound);             // symlink out of web/
  EXPECT_EQ(root.find("/up/secret.txt").outcome, WebRoot::Outcome::NotFound);        // through a linked folder
  EXPECT_EQ(root.find("/.hidden").outcome, WebRoot::Outcome::NotFound);
}

TEST(ServerWebRoot, MissingFolderIsAnError) { EXPECT_THROW(WebRoot("/nonexistent/orthosim/web"), std::runtime_error); }

TEST(ServerRequestTarget, SplitsQueryAndDecodesEscapes) {
  const auto t = net::parseRequestTarget("/a%20b/%2e%2e/c?x=%2e");
  ASSERT_TRUE(t);
  EXPECT_EQ(t->path, "/a b/../c");  // decoded, so WebRoot sees the ".." and refuses it
  EXPECT_EQ(t->query, "x=%2e");
  EXPECT_FALSE(net::parseRequestTarget("http://example.com/"));
  EXPECT_FALSE(net::parseRequestTarget("*"));
  EXPECT_FALSE(net::parseRequestTarget(""));
  EXPECT_FALSE(net::parseRequestTarget("/a%2"));
  EXPECT_FALSE(net::parseRequestTarget("/a%zz"));
  EXPECT_FALSE(net::parseRequestTarget("/a%00b"));
}

TEST(ServerMimeType, KnowsThePageTypes) {
  EXPECT_EQ(net::mimeType("index.html"), "text/html; charset=utf-8");
  EXPECT_EQ(net::mimeType("app.JS"), "text/javascript; charset=utf-8");
  EXPECT_EQ(net::mimeType("style.css"), "text/css; charset=utf-8");
  EXPECT_EQ(net::mimeType("skin.png"), "image/png");
  EXPECT_EQ(net::mimeType("skin.jpg"), "image/jpeg");
  EXPECT_EQ(net::mimeType("skin.jpeg"), "image/jpeg");
  EXPECT_EQ(net::mimeType("case.json"), "application/json");
  EXPECT_EQ(net::mimeType("run.sh"), "application/octet-stream");
}

}  // namespace
}  // namespace orthosim
