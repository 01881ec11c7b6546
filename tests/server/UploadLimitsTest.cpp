// Uploads are streamed to a file, at most --max-uploads at once: one more is refused at its headers
// (503 too_many_uploads, Retry-After) until one ends, and the body's file goes however the upload
// ends, the client leaving mid-body included. Every error of the upload routes names its field.
#include <gtest/gtest.h>
#include <unistd.h>

#include <boost/asio/connect.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/write.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "FormUpload.hpp"
#include "HttpTestClient.hpp"
#include "ServerProcess.hpp"
#include "TestWait.hpp"

namespace http = boost::beast::http;

namespace orthosim {
namespace {
namespace fs = std::filesystem;
using nlohmann::json;
using namespace std::chrono_literals;
using test::Part;

class UploadLimits : public ::testing::Test {
 protected:
  void SetUp() override {
    data_ = fs::temp_directory_path() / ("orthosim_upload_limits_" + std::to_string(::getpid()) + "_" +
                                         ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(data_);
  }
  void TearDown() override { fs::remove_all(data_); }

  // The files in the data folder's imports/ (bodies being received, files being staged).
  std::size_t importFiles() const {
    std::error_code ec;
    if (!fs::is_directory(data_ / "imports", ec)) return 0;
    return static_cast<std::size_t>(std::distance(fs::directory_iterator(data_ / "imports"), fs::directory_iterator()));
  }
  static test::HttpReply send(unsigned short port, const std::string& request) {
    const std::vector<test::HttpReply> replies = test::httpRaw(port, request);
    if (replies.size() != 1) throw std::runtime_error("expected one reply, got " + std::to_string(replies.size()));
    return replies[0];
  }
  // A patient's form without its surfaces: refused (missing_file) after its body is read.
  static std::string incompletePatient() {
    return test::formRequest("/api/patients", {{"id", "", "p1"}, {"name", "", "Test"}});
  }

  fs::path data_;
};

TEST_F(UploadLimits, OneUploadMoreThanAllowedIsRefusedAtItsHeadersUntilTheFirstEnds) {
  test::ServerProcess server({"--data", data_.string(), "--no-warm-up", "--max-uploads", "1"});
  // The first upload: its headers and the start of a 10 MB body, then nothing more for now.
  boost::asio::io_context io;
  boost::asio::ip::tcp::socket first(io);
  first.connect({boost::asio::ip::make_address("127.0.0.1"), server.port()});
  boost::asio::write(
      first, boost::asio::buffer(
                 std::string("POST /api/patients HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: multipart/form-data; "
                             "boundary=B\r\nContent-Length: 10000000\r\n\r\n--B\r\nContent-Disposition: form-data; "
                             "name=\"skin\"; filename=\"skin.stl\"\r\n\r\n") +
                 std::string(100000, 's')));
  // Its body goes to a file as it comes.
  ASSERT_TRUE(test::waitUntil([&] { return importFiles() == 1; }, 10s)) << "no body file in imports/";

  for (const char* path : {"/api/patients", "/api/scans"}) {
    const test::HttpReply refused = send(server.port(), test::formRequest(path, {{"id", "", "p2"}}));
    EXPECT_EQ(refused.result(), http::status::service_unavailable) << refused.body();
    const json error = json::parse(refused.body());
    EXPECT_EQ(error["error"], "too_many_uploads") << refused.body();
    EXPECT_EQ(error["path"], path);
    EXPECT_EQ(error.at("field"), "");
    EXPECT_FALSE(refused[http::field::retry_after].empty());
  }
  EXPECT_EQ(importFiles(), 1u) << "the refused uploads left files";

  // The client leaves mid-body: its file goes, and its slot with it.
  first.close();
  ASSERT_TRUE(test::waitUntil([&] { return importFiles() == 0; }, 10s)) << "the body file stayed";
  test::HttpReply again;
  ASSERT_TRUE(test::waitUntil(
      [&] {
        again = send(server.port(), incompletePatient());
        return again.result() != http::status::service_unavailable;
      },
      10s, 100ms))
      << again.body();
  EXPECT_EQ(again.result(), http::status::bad_request) << again.body();
  EXPECT_EQ(json::parse(again.body())["error"], "missing_file") << again.body();
  EXPECT_EQ(importFiles(), 0u);
}

TEST_F(UploadLimits, EveryUploadErrorNamesItsFieldInPlainWords) {
  test::ServerProcess server({"--data", data_.string(), "--no-warm-up"});
  auto refused = [&](const std::string& request, const std::string& code, const std::string& field,
                     const std::vector<std::string>& words) {
    const test::HttpReply reply = send(server.port(), request);
    EXPECT_EQ(reply.result(), http::status::bad_request) << reply.body();
    const json error = json::parse(reply.body());
    EXPECT_EQ(error["error"], code) << reply.body();
    EXPECT_EQ(error.at("field"), field) << reply.body();
    const std::string message = error["message"];
    for (const std::string& w : words) EXPECT_NE(message.find(w), std::string::npos) << message;
    for (const char* internal : {"json.exception", "assimp", "vtk", "/tmp/", "/imports/"})
      EXPECT_EQ(message.find(internal), std::string::npos) << message;
    EXPECT_EQ(importFiles(), 0u) << "left behind after " << code;
  };
  const std::string invalid = "Dr \xff\xfe Smith";
  refused(test::formRequest("/api/patients", {{"id", "", "p1"}, {"name", "", invalid}}), "bad_field", "name",
          {"name: not valid UTF-8"});
  for (const char* field :
       {"id", "units", "oral_cavity", "cuts", "series", "skin_threshold", "mandible_seed", "tissue_labels"})
    refused(test::formRequest("/api/patients", {{field, "", "\xc3("}}), "bad_field", field,
            {std::string(field) + ": not valid UTF-8"});
  refused(test::formRequest("/api/patients", {{"id", "", "p1"}, {"cuts", "", "le_fort_1, zzz"}}), "bad_field", "cuts",
          {"'zzz'", "le_fort_1", "bsso", "genioplasty"});
  refused(test::formRequest("/api/patients", {{"na\xffme", "", "x"}}), "bad_field", "na?me", {"not valid UTF-8"});
  refused(test::formRequest("/api/scans", {{"dicom", "sc\xffn.dcm", "x"}}), "bad_file", "dicom",
          {"file name is not valid UTF-8"});
  // Refused on its headers: no form field at fault, but the field is there.
  const test::HttpReply foreign =
      send(server.port(), test::formRequest("/api/patients", {{"id", "", "p1"}}, "Origin: http://evil.example\r\n"));
  EXPECT_EQ(foreign.result(), http::status::forbidden) << foreign.body();
  EXPECT_EQ(json::parse(foreign.body()).at("field"), "") << foreign.body();
  // A malformed form as a whole: field "body".
  refused(
      "POST /api/patients HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\nContent-Type: multipart/form-data; "
      "boundary=B\r\nContent-Length: 17\r\n\r\n--B\r\nno headers\r\n",
      "bad_form", "body", {"form"});
  refused(
      "POST /api/scans HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\nContent-Type: application/json\r\n"
      "Content-Length: 2\r\n\r\n{}",
      "bad_form", "body", {"multipart/form-data"});
}

}  // namespace
}  // namespace orthosim
