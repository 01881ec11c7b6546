// A CT scan imported from the page without leaving it: its files (a folder's, or a .zip) are staged
// once and listed by series; a preview segments it with the thresholds and seeds given and shows the
// slices; the import makes the case with its suggested landmarks. Every refusal names its field, a
// hostile zip is refused, and nothing staged is left behind by a refusal, an expiry or an import.
#include <gtest/gtest.h>
#include <unistd.h>
#include <zip.h>

#include <filesystem>
#include <fstream>
#include <future>
#include <iostream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <thread>

#include "FormUpload.hpp"
#include "HttpTestClient.hpp"
#include "ServerProcess.hpp"
#include "phantom/PhantomCase.hpp"
#include "phantom/PhantomCt.hpp"
#include "render/PngFile.hpp"
#include "volume/DicomSeries.hpp"

namespace http = boost::beast::http;

namespace orthosim {
namespace {
namespace fs = std::filesystem;
using nlohmann::json;
using namespace std::chrono_literals;

using test::Part;
using test::readFile;

std::string multipart(const std::string& path, const std::vector<Part>& parts) {
  return test::formRequest(path, parts);
}

test::HttpReply send(unsigned short port, const std::string& raw, std::chrono::seconds silence = 10s) {
  const std::vector<test::HttpReply> replies = test::httpRaw(port, raw, silence);
  if (replies.size() != 1) throw std::runtime_error("expected one reply, got " + std::to_string(replies.size()));
  return replies[0];
}

test::HttpReply postJson(unsigned short port, const std::string& path, const json& body,
                         const std::string& method = "POST", std::chrono::seconds silence = 10s) {
  const std::string text = body.dump();
  return send(port,
              method + " " + path +
                  " HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\nContent-Type: application/json\r\n"
                  "Content-Length: " +
                  std::to_string(text.size()) + "\r\n\r\n" + text,
              silence);
}

// A toy head at 2 mm voxels: a block of soft tissue holding the skull above (a dense core in a
// 500 HU shell, so that a bone threshold between the two changes the skull) and the mandible below
// and in front, 20 mm apart.
CtVolume toyHead() {
  CtVolume v;
  v.size = Eigen::Vector3i(60, 60, 70);
  v.directions = Eigen::Matrix3d::Identity() * 2.0;
  v.origin = Eigen::Vector3d(-59, -59, -69);
  v.values.assign(size_t(v.count()), -1000.f);
  auto in = [](const Eigen::Vector3d& p, Eigen::Vector3d lo, Eigen::Vector3d hi) {
    return (p.array() >= lo.array()).all() && (p.array() <= hi.array()).all();
  };
  for (int k = 0; k < v.size.z(); ++k)
    for (int j = 0; j < v.size.y(); ++j)
      for (int i = 0; i < v.size.x(); ++i) {
        const Eigen::Vector3d p = v.position(Eigen::Vector3d(i, j, k));
        float& value = v.values[size_t(v.index(i, j, k))];
        if (in(p, {-45, -45, -55}, {45, 45, 55})) value = 40;
        if (in(p, {-30, -30, 10}, {30, 30, 45})) value = 500;
        if (in(p, {-22, -22, 18}, {22, 22, 37})) value = 1200;
        if (in(p, {-30, -40, -40}, {30, 0, -10})) value = 1200;
      }
  return v;
}

class ScanUpload : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    work_ = new fs::path(fs::temp_directory_path() / ("orthosim_scan_upload_" + std::to_string(::getpid())));
    fs::remove_all(*work_);
    const CtVolume head = toyHead();
    DicomWriteOptions a;
    a.seriesDescription = "toy head";
    writeDicomSeries(head, (*work_ / "one").string(), a);
    DicomWriteOptions b = a;
    b.seriesDescription = "toy head again";
    b.fileNamePrefix = "SE2_";
    writeDicomSeries(head, (*work_ / "two").string(), a);
    writeDicomSeries(head, (*work_ / "two").string(), b);
    DicomWriteOptions mr = a;
    mr.modality = "MR";
    writeDicomSeries(head, (*work_ / "mr").string(), mr);
  }
  static void TearDownTestSuite() {
    fs::remove_all(*work_);
    delete work_;
  }
  void SetUp() override {
    data_ = *work_ / ("data_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(data_);
  }
  void TearDown() override { fs::remove_all(data_); }

  std::vector<std::string> serverArgs(std::vector<std::string> more = {}) const {
    std::vector<std::string> args{"--data", data_.string(), "--no-warm-up"};
    args.insert(args.end(), more.begin(), more.end());
    return args;
  }
  // The files of a series folder as a browser sends a picked folder: names with the folder's path.
  static std::vector<Part> folderParts(const std::string& series, const std::string& field = "dicom") {
    std::vector<Part> parts;
    for (const auto& e : fs::directory_iterator(*work_ / series))
      parts.push_back({field, "Patient X/" + series + "/" + e.path().filename().string(), readFile(e.path())});
    return parts;
  }
  // A zip of `entries` (name -> bytes); `symlink`: the entry of that name is a Unix symbolic link.
  static std::string zipOf(const std::vector<std::pair<std::string, std::string>>& entries,
                           const std::string& symlink = "") {
    const fs::path path = *work_ / "archive.zip";
    fs::remove(path);
    zipFile z = zipOpen64(path.string().c_str(), APPEND_STATUS_CREATE);
    for (const auto& [name, bytes] : entries) {
      zip_fileinfo info{};
      if (name == symlink) info.external_fa = (0120777u << 16);
      // version made by: 3 (Unix) in the high byte, so that the mode is read
      zipOpenNewFileInZip4_64(z, name.c_str(), &info, nullptr, 0, nullptr, 0, nullptr, Z_DEFLATED, 9, 0, -MAX_WBITS,
                              DEF_MEM_LEVEL, Z_DEFAULT_STRATEGY, nullptr, 0, 3 << 8, 0, 0);
      zipWriteInFileInZip(z, bytes.data(), unsigned(bytes.size()));
      zipCloseFileInZip(z);
    }
    zipClose(z, nullptr);
    const std::string out = readFile(path);
    fs::remove(path);
    return out;
  }
  static std::vector<std::pair<std::string, std::string>> seriesEntries(const std::string& series) {
    std::vector<std::pair<std::string, std::string>> entries;
    for (const auto& e : fs::directory_iterator(*work_ / series))
      entries.push_back({"export/" + series + "/" + e.path().filename().string(), readFile(e.path())});
    return entries;
  }
  json stage(unsigned short port, const std::vector<Part>& parts, http::status expected = http::status::created) {
    const test::HttpReply reply = send(port, multipart("/api/scans", parts), 120s);  // reads a CT series
    EXPECT_EQ(reply.result(), expected) << reply.body();
    return json::parse(reply.body());
  }
  std::vector<std::string> staged() const {
    std::vector<std::string> found;
    if (fs::is_directory(data_ / "imports"))
      for (const auto& e : fs::directory_iterator(data_ / "imports")) found.push_back(e.path().filename().string());
    return found;
  }
  static long bone(const json& preview) {
    long n = 0;
    for (const json& image : preview["images"]) n += image["pixels"]["skull"].get<long>();
    return n;
  }

  static inline fs::path* work_ = nullptr;
  fs::path data_;
};

TEST_F(ScanUpload, AFolderAndAZipAreStagedAndTheirSeriesListed) {
  test::ServerProcess server(serverArgs());
  const json folder = stage(server.port(), folderParts("one"));
  const std::string token = folder["token"];
  EXPECT_EQ(token.size(), 32u);
  ASSERT_EQ(folder["series"].size(), 1u) << folder.dump();
  EXPECT_EQ(folder["series"][0]["modality"], "CT");
  EXPECT_EQ(folder["series"][0]["description"], "toy head");
  EXPECT_EQ(folder["series"][0]["files"], 70);
  EXPECT_EQ(folder["series"][0]["rows"], 60);
  EXPECT_NE(folder["read"].get<std::string>().find("CT"), std::string::npos) << folder.dump();
  // The files under their base names only (the folder's path in their names is dropped).
  const fs::path series = data_ / "imports" / ("scan-" + token) / "series";
  EXPECT_TRUE(fs::exists(series / "IM0001.dcm")) << "staged as base names";
  EXPECT_EQ(std::distance(fs::directory_iterator(series), fs::directory_iterator()), 70);

  const json zipped = stage(server.port(), {{"dicom_zip", "scan.zip", zipOf(seriesEntries("one"))}});
  ASSERT_EQ(zipped["series"].size(), 1u) << zipped.dump();
  EXPECT_EQ(zipped["series"][0]["uid"], folder["series"][0]["uid"]);
  EXPECT_EQ(staged().size(), 2u);

  // Discarded: its folder goes.
  EXPECT_EQ(postJson(server.port(), "/api/scans/" + token, json::object(), "DELETE").result(), http::status::ok);
  EXPECT_FALSE(fs::exists(data_ / "imports" / ("scan-" + token)));
}

TEST_F(ScanUpload, TwoSeriesAreListedAndOneMustBeChosen) {
  test::ServerProcess server(serverArgs());
  const json staged2 = stage(server.port(), folderParts("two"));
  ASSERT_EQ(staged2["series"].size(), 2u) << staged2.dump();
  const std::string token = staged2["token"];
  const test::HttpReply unchosen = postJson(server.port(), "/api/scans/" + token + "/preview", json::object());
  EXPECT_EQ(unchosen.result(), http::status::bad_request);
  const json several = json::parse(unchosen.body());
  EXPECT_EQ(several["error"], "several_series") << several.dump();
  ASSERT_EQ(several["series"].size(), 2u);
  std::set<std::string> descriptions{several["series"][0]["description"], several["series"][1]["description"]};
  EXPECT_EQ(descriptions, (std::set<std::string>{"toy head", "toy head again"}));
  EXPECT_EQ(several["series"][0]["files"], 70);

  const json chosen = json::parse(
      postJson(server.port(), "/api/scans/" + token + "/preview", {{"series", several["series"][1]["uid"]}}).body());
  EXPECT_EQ(chosen["series"], several["series"][1]["uid"]) << chosen.dump();

  // The one-step upload says the same, and keeps nothing.
  std::vector<Part> parts = folderParts("two");
  parts.push_back({"id", "", "two-series"});
  const test::HttpReply once = send(server.port(), multipart("/api/patients", parts));
  EXPECT_EQ(once.result(), http::status::bad_request);
  const json error = json::parse(once.body());
  EXPECT_EQ(error["error"], "several_series") << error.dump();
  EXPECT_EQ(error["series"].size(), 2u);
  EXPECT_EQ(staged().size(), 1u) << "only the staged scan";
  EXPECT_FALSE(fs::exists(data_ / "patients" / "two-series"));
}

TEST_F(ScanUpload, APreviewShowsTheSlicesAndAThresholdChangesThem) {
  test::ServerProcess server(serverArgs());
  const std::string token = stage(server.port(), folderParts("one"))["token"];
  const test::HttpReply first = postJson(server.port(), "/api/scans/" + token + "/preview", json::object());
  ASSERT_EQ(first.result(), http::status::ok) << first.body();
  const json preview = json::parse(first.body());
  EXPECT_DOUBLE_EQ(preview["skin_threshold"].get<double>(), -400);  // Hounsfield defaults
  EXPECT_DOUBLE_EQ(preview["bone_threshold"].get<double>(), 300);
  EXPECT_FALSE(preview["notes"].empty());
  ASSERT_EQ(preview["images"].size(), 3u);
  EXPECT_EQ(preview["images"][0]["plane"], "axial");
  EXPECT_EQ(preview["images"][1]["plane"], "sagittal");
  EXPECT_EQ(preview["images"][2]["plane"], "coronal");
  for (const json& image : preview["images"]) {
    const std::string src = image["src"];
    ASSERT_EQ(src.rfind("data:image/png;base64,iVBORw0KGgo", 0), 0u) << src.substr(0, 40);  // PNG's signature
    EXPECT_GT(image["pixels"]["tissue"].get<long>(), 0) << image.dump().substr(0, 300);
    EXPECT_EQ(image["column"].size(), 3u);
  }
  // The sagittal slice maps its pixels to LPS: its rows run down (-z), its columns posterior (+y).
  EXPECT_LT(preview["images"][1]["row"][2].get<double>(), 0);
  EXPECT_GT(preview["images"][1]["column"][1].get<double>(), 0);
  EXPECT_GT(preview["images"][1]["pixels"]["mandible"].get<long>(), 0);

  // A bone threshold above the skull's shell (500 HU) leaves its core only.
  const json denser =
      json::parse(postJson(server.port(), "/api/scans/" + token + "/preview", {{"bone_threshold", 800}}).body());
  EXPECT_DOUBLE_EQ(denser["bone_threshold"].get<double>(), 800) << denser.dump().substr(0, 500);
  EXPECT_LT(bone(denser), bone(preview) * 0.8) << bone(denser) << " vs " << bone(preview);
  EXPECT_NE(denser["images"][2]["src"], preview["images"][2]["src"]);
  EXPECT_NE(denser["notes"][0], preview["notes"][0]);
}

TEST_F(ScanUpload, SeedsOffTheBoneAndBadFieldsAreRefusedNamingThem) {
  test::ServerProcess server(serverArgs());
  const std::string token = stage(server.port(), folderParts("one"))["token"];
  const std::string preview = "/api/scans/" + token + "/preview";
  auto refused = [&](const json& body, const std::string& code, const std::string& field, const std::string& words) {
    const test::HttpReply reply = postJson(server.port(), preview, body);
    EXPECT_EQ(reply.result(), http::status::bad_request) << reply.body();
    const json e = json::parse(reply.body());
    EXPECT_EQ(e["error"], code) << reply.body();
    EXPECT_EQ(e.value("field", ""), field) << reply.body();
    EXPECT_NE(e["message"].get<std::string>().find(words), std::string::npos) << reply.body();
  };
  refused({{"mandible_seed", {0, 0, 0}}}, "segmentation_failed", "mandible_seed", "mandible seed");  // between the jaws
  refused({{"skull_seed", "0,0,-60"}}, "segmentation_failed", "skull_seed", "skull seed");
  refused({{"bone_threshold", "abc"}}, "bad_field", "bone_threshold", "bone_threshold: 'abc' is not a finite number");
  refused({{"skin_threshold", "inf"}}, "bad_field", "skin_threshold", "skin_threshold");
  refused({{"skull_seed", "1,2"}}, "bad_field", "skull_seed", "not a point");
  refused({{"mandible_seed", {1, "x", 3}}}, "bad_field", "mandible_seed", "mandible_seed");
  refused({{"series", "../etc"}}, "bad_field", "series", "not a SeriesInstanceUID");
  refused({{"series", "1.2.3"}}, "bad_field", "series", "not in the scan");
  refused({{"colour", "red"}}, "bad_field", "colour", "no such field");
  refused({{"skin_threshold", 500}, {"bone_threshold", 200}}, "bad_field", "bone_threshold", "above the skin");
  // A seed on the bone is taken.
  const test::HttpReply seeded = postJson(server.port(), preview, {{"mandible_seed", {0, -20, -25}}});
  EXPECT_EQ(seeded.result(), http::status::ok) << seeded.body().substr(0, 500);

  // The one-step upload checks its form fields the same way.
  std::vector<Part> parts = folderParts("one");
  parts.push_back({"id", "", "bad-fields"});
  parts.push_back({"mandible_seed", "", "1,2,nan"});
  const json e = json::parse(send(server.port(), multipart("/api/patients", parts)).body());
  EXPECT_EQ(e["field"], "mandible_seed") << e.dump();
  EXPECT_EQ(staged().size(), 1u);

  // An import's own fields.
  const test::HttpReply badId = postJson(server.port(), "/api/scans/" + token + "/import", {{"id", "../x"}});
  EXPECT_EQ(json::parse(badId.body())["field"], "id") << badId.body();
  EXPECT_EQ(staged().size(), 1u) << "a refused import keeps the scan";
}

TEST_F(ScanUpload, HostileZipsAreRefusedAndLeaveNothing) {
  test::ServerProcess server(serverArgs());
  auto refused = [&](const std::string& zip, const std::string& words) {
    const json e = stage(server.port(), {{"dicom_zip", "scan.zip", zip}}, http::status::bad_request);
    EXPECT_EQ(e["error"], "bad_zip") << e.dump();
    EXPECT_EQ(e["field"], "dicom_zip") << e.dump();
    EXPECT_NE(e["message"].get<std::string>().find(words), std::string::npos) << e.dump();
    EXPECT_TRUE(staged().empty()) << "left behind after: " << words;
  };
  auto entries = seriesEntries("one");
  entries.push_back({"../x", "escape"});
  refused(zipOf(entries), "leaves the archive's folder");
  refused(zipOf({{"/etc/cron.d/x", "escape"}}), "absolute path");
  refused(zipOf({{"IM0001.dcm", "x"}, {"link", "/etc/passwd"}}, "link"), "symbolic link");
  // 64 MiB of zeros: about 64 KiB packed, a ratio of about 1000.
  refused(zipOf({{"bomb.dcm", std::string(64 << 20, '\0')}}), "zip bomb");
  refused("PK not a zip at all", "not a zip archive");
  // And through the one-step upload.
  const json e = json::parse(
      send(server.port(), multipart("/api/patients", {{"id", "", "zipped"}, {"dicom_zip", "scan.zip", zipOf(entries)}}))
          .body());
  EXPECT_EQ(e["error"], "bad_zip") << e.dump();
  EXPECT_TRUE(staged().empty());
  EXPECT_FALSE(fs::exists(data_ / "patients" / "zipped"));
}

TEST_F(ScanUpload, UnknownExpiredAndTooManyScans) {
  test::ServerProcess server(serverArgs({"--scan-expiry", "2", "--max-staged-scans", "1"}));
  const json unknown = json::parse(
      postJson(server.port(), "/api/scans/0123456789abcdef0123456789abcdef/preview", json::object()).body());
  EXPECT_EQ(unknown["error"], "unknown_scan");
  EXPECT_EQ(postJson(server.port(), "/api/scans/nonsense/preview", json::object()).result(), http::status::not_found);

  const std::string token = stage(server.port(), folderParts("one"))["token"];
  const json full = stage(server.port(), folderParts("one"), http::status::service_unavailable);
  EXPECT_EQ(full["error"], "too_many_scans") << full.dump();
  EXPECT_EQ(staged().size(), 1u);
  std::this_thread::sleep_for(3s);
  const test::HttpReply expired = postJson(server.port(), "/api/scans/" + token + "/preview", json::object());
  EXPECT_EQ(expired.result(), http::status::not_found) << expired.body();
  EXPECT_TRUE(staged().empty()) << "an expired scan's folder is removed";
  stage(server.port(), folderParts("one"));  // room again
}

TEST_F(ScanUpload, AnMrSeriesIsRefusedAndLeavesNothing) {
  test::ServerProcess server(serverArgs());
  const json e = stage(server.port(), folderParts("mr"), http::status::bad_request);
  EXPECT_EQ(e["error"], "bad_scan") << e.dump();
  EXPECT_NE(e["message"].get<std::string>().find("MR"), std::string::npos) << e.dump();
  EXPECT_EQ(e["message"].get<std::string>().find(data_.string()), std::string::npos) << e.dump();
  EXPECT_TRUE(staged().empty());
  std::vector<Part> parts = folderParts("mr");
  parts.push_back({"id", "", "mr-patient"});
  const test::HttpReply once = send(server.port(), multipart("/api/patients", parts));
  EXPECT_EQ(once.result(), http::status::bad_request) << once.body();
  EXPECT_NE(once.body().find("MR"), std::string::npos) << once.body();
  EXPECT_TRUE(staged().empty());
  EXPECT_FALSE(fs::exists(data_ / "patients" / "mr-patient"));
}

// The phantom's CT, staged, previewed and imported: a case in the library with suggested landmarks.
TEST_F(ScanUpload, ThePhantomsCtBecomesACaseWithSuggestedLandmarks) {
  const fs::path phantom = *work_ / "phantom", series = *work_ / "phantom-ct";
  writePhantomCase(0, phantom.string());
  writeDicomSeries(phantomCt(phantom.string()).ct, series.string());
  std::vector<Part> parts;
  for (const auto& e : fs::directory_iterator(series))
    parts.push_back({"dicom", "ct/" + e.path().filename().string(), readFile(e.path())});
  test::ServerProcess server(serverArgs({"--max-upload-mb", "1024"}));
  const std::string token = stage(server.port(), parts)["token"];
  const test::HttpReply preview =
      postJson(server.port(), "/api/scans/" + token + "/preview", json::object(), "POST", 120s);  // segments it
  ASSERT_EQ(preview.result(), http::status::ok) << preview.body().substr(0, 1000);
  const json p = json::parse(preview.body());
  EXPECT_NE(p["images"][0]["placed"].get<std::string>().find("occlusal"), std::string::npos)
      << p["images"][0]["placed"];
  EXPECT_GT(p["images"][0]["pixels"]["mandible"].get<long>(), 0);
  EXPECT_GT(p["images"][0]["pixels"]["skull"].get<long>(), 0);

  auto importing = std::async(std::launch::async, [&] {
    return postJson(server.port(), "/api/scans/" + token + "/import",
                    {{"id", "ct-patient"},
                     {"name", "CT patient"},
                     {"cuts", "le_fort_1,bsso"},
                     {"bone_threshold", p["bone_threshold"]}},
                    "POST", 300s);  // a scan's import takes tens of seconds
  });
  // Beside the import, its stage is answered at once.
  std::set<std::string> stages;
  while (importing.wait_for(200ms) != std::future_status::ready) {
    const test::HttpReply status = test::httpGet(server.port(), "/api/scans/" + token);
    if (status.result() != http::status::ok) continue;  // before the import begins, or after it ends
    const json j = json::parse(status.body());
    if (!j["stage"].get<std::string>().empty()) stages.insert(j["stage"].get<std::string>());
  }
  for (const std::string& s : stages) std::cout << "stage: " << s << "\n";
  EXPECT_TRUE(stages.count("segmenting") || stages.count("making the surfaces")) << stages.size();
  EXPECT_TRUE(stages.count("checking and repairing the surfaces")) << stages.size();
  const test::HttpReply imported = importing.get();
  ASSERT_EQ(imported.result(), http::status::created) << imported.body();
  const json r = json::parse(imported.body());
  EXPECT_EQ(r["case"]["id"], "ct-patient");
  EXPECT_FALSE(r["scan"].empty()) << r.dump();
  EXPECT_NE(r["scan"][0].get<std::string>().find("the scan"), std::string::npos) << r["scan"].dump();
  EXPECT_EQ(r.dump().find(data_.string()), std::string::npos) << "no server folder in the reply";
  EXPECT_FALSE(r["suggested"].empty()) << r.dump();
  EXPECT_TRUE(fs::exists(data_ / "patients" / "ct-patient" / "case.json"));
  EXPECT_TRUE(staged().empty()) << "the import removes its scan";
  const json cases = json::parse(test::httpGet(server.port(), "/api/cases").body());
  bool listed = false;
  for (const json& c : cases["cases"]) listed = listed || c["id"] == "ct-patient";
  EXPECT_TRUE(listed);
  EXPECT_EQ(postJson(server.port(), "/api/scans/" + token + "/preview", json::object()).result(),
            http::status::not_found);
}

}  // namespace
}  // namespace orthosim
