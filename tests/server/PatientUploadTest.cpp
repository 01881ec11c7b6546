// A new patient uploaded over HTTP: the phantom's own exported surfaces become a
// case in the list that opens and previews, is still there after a restart, and each bad upload gets
// its own clear error and leaves no case and no staged file behind.
#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/Core>
#include <array>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "FormUpload.hpp"
#include "HttpTestClient.hpp"
#include "LabelMapFiles.hpp"
#include "ServerProcess.hpp"
#include "WsTestClient.hpp"
#include "phantom/PhantomCase.hpp"

namespace http = boost::beast::http;

namespace orthosim {
namespace {
namespace fs = std::filesystem;
using nlohmann::json;
using namespace std::chrono_literals;

using test::Part;
using test::readFile;

// The raw request a browser's FormData makes, with Connection: close.
std::string uploadRequest(const std::vector<Part>& parts, const std::string& extraHeaders = "") {
  return test::formRequest("/api/patients", parts, extraHeaders);
}

class PatientUpload : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    export_ = new fs::path(fs::temp_directory_path() / ("orthosim_upload_export_" + std::to_string(::getpid())));
    writePhantomCase(0, export_->string());
  }
  static void TearDownTestSuite() {
    fs::remove_all(*export_);
    delete export_;
  }
  void SetUp() override {
    data_ = fs::temp_directory_path() / ("orthosim_upload_data_" + std::to_string(::getpid()) + "_" +
                                         ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(data_);
  }
  void TearDown() override {
    fs::remove_all(data_);
    fs::remove_all(data_.string() + "-1MiB");
  }

  static Part file(const std::string& field, const std::string& name) {
    return {field, name, readFile(*export_ / name)};
  }
  static std::vector<Part> phantomParts(const std::string& id) {
    return {{"id", "", id},
            {"name", "", "Test patient"},
            {"units", "", "auto"},
            {"cuts", "", "le_fort_1,bsso"},
            file("skin", "skin.obj"),
            file("skull", "skull.stl"),
            file("mandible", "mandible.stl"),
            file("cavity", "oral_cavity.stl"),
            file("texture", "skin.jpg"),
            file("landmarks", "landmarks.json")};
  }
  std::vector<std::string> serverArgs(std::vector<std::string> more = {}) const {
    std::vector<std::string> args{"--data", data_.string(), "--no-warm-up"};
    args.insert(args.end(), more.begin(), more.end());
    return args;
  }
  static test::HttpReply upload(unsigned short port, const std::vector<Part>& parts, const std::string& headers = "") {
    const std::vector<test::HttpReply> replies =
        test::httpRaw(port, uploadRequest(parts, headers), std::chrono::seconds(300));
    if (replies.size() != 1) throw std::runtime_error("expected one reply, got " + std::to_string(replies.size()));
    return replies[0];
  }
  // The ids of /api/cases.
  static std::vector<std::string> caseIds(unsigned short port) {
    std::vector<std::string> ids;
    const json cases = json::parse(test::httpGet(port, "/api/cases").body());
    for (const json& c : cases["cases"]) ids.push_back(c["id"]);
    return ids;
  }
  // What the data folder holds of imports: patient folders and staged uploads.
  std::vector<std::string> importsOnDisk() const {
    std::vector<std::string> found;
    for (const char* sub : {"patients", "imports"})
      if (fs::is_directory(data_ / sub))
        for (const auto& e : fs::directory_iterator(data_ / sub))
          found.push_back(std::string(sub) + "/" + e.path().filename().string());
    std::sort(found.begin(), found.end());
    return found;
  }

  static inline fs::path* export_ = nullptr;
  fs::path data_;
};

TEST_F(PatientUpload, ThePhantomsSurfacesBecomeACaseThatOpensPreviewsAndStays) {
  {
    test::ServerProcess server(serverArgs());
    const test::HttpReply reply = upload(server.port(), phantomParts("patient-1"));
    ASSERT_EQ(reply.result(), http::status::created) << reply.body();
    const json created = json::parse(reply.body());
    EXPECT_EQ(created["case"]["id"], "patient-1");
    EXPECT_EQ(created["case"]["name"], "Test patient");
    EXPECT_EQ(created["case"]["source"], "import");
    EXPECT_EQ(created["scale"], 1.0);
    EXPECT_EQ(created["built"], json::array());  // the oral cavity came as a file: none is built
    const std::vector<std::string> ids = caseIds(server.port());
    EXPECT_NE(std::find(ids.begin(), ids.end(), "patient-1"), ids.end());
    EXPECT_EQ(importsOnDisk(), std::vector<std::string>{"patients/patient-1"});  // nothing staged is left

    // It plans like any case: open, move the maxilla its Le Fort I made, get a converged preview.
    test::WsTestClient ws(server.port());
    EXPECT_EQ(ws.request({{"type", "open"}, {"case", "patient-1"}})["type"], "opening");
    const json opened = ws.waitFor("opened", 180s);
    EXPECT_EQ(opened["cuts"][0]["kind"], "le_fort_1") << opened.dump();
    const json poses = ws.request({{"type", "set_poses"}, {"poses", {{"maxilla", {{"anterior_mm", 2.0}}}}}});
    ASSERT_EQ(poses["type"], "poses") << poses.dump();
    const json preview = ws.waitFor("preview", 120s);
    EXPECT_TRUE(preview["figures"]["converged"].get<bool>()) << preview.dump();
    EXPECT_GT(preview["figures"]["landmarks"]["labrale_superius"]["anterior_mm"].get<double>(), 0.5);
    ws.close();

    // The same id again is refused, and leaves the first alone.
    const test::HttpReply again = upload(server.port(), phantomParts("patient-1"));
    EXPECT_EQ(again.result(), http::status::conflict);
    EXPECT_EQ(json::parse(again.body())["error"], "case_exists");
  }
  test::ServerProcess restarted(serverArgs());  // what a surgeon imported is still there
  const std::vector<std::string> ids = caseIds(restarted.port());
  EXPECT_NE(std::find(ids.begin(), ids.end(), "patient-1"), ids.end());
}

TEST_F(PatientUpload, EachBadUploadGetsItsOwnErrorAndLeavesNothing) {
  test::ServerProcess server(serverArgs());
  auto refused = [&](std::vector<Part> parts, http::status status, const std::string& code, const std::string& field,
                     const std::string& words, const std::string& headers = "") {
    const test::HttpReply reply = upload(server.port(), parts, headers);
    EXPECT_EQ(reply.result(), status) << reply.body();
    const json error = json::parse(reply.body());
    EXPECT_EQ(error["error"], code) << reply.body();
    if (!field.empty()) EXPECT_EQ(error.value("field", ""), field) << reply.body();
    EXPECT_NE(error["message"].get<std::string>().find(words), std::string::npos) << reply.body();
    // Messages name the user's files, never the server's folders.
    EXPECT_EQ(error["message"].get<std::string>().find(data_.string()), std::string::npos) << reply.body();
    EXPECT_TRUE(importsOnDisk().empty()) << "left behind after " << code;
  };
  // Small surfaces under the 1 MiB limit: a box's worth, never imported here.
  auto small = [](std::vector<Part> parts) {
    for (Part& p : parts)
      if (!p.fileName.empty()) p.data = p.data.substr(0, 1000);
    return parts;
  };
  std::vector<Part> parts = small(phantomParts("../evil"));
  refused(parts, http::status::bad_request, "bad_name", "id", "not a case identifier");

  parts = small(phantomParts("p2"));
  parts[4].fileName = "exports/skin.stl";
  refused(parts, http::status::bad_request, "bad_file", "skin", "has a path in it");

  parts = small(phantomParts("p2"));
  parts.erase(parts.begin() + 6);  // no mandible
  refused(parts, http::status::bad_request, "missing_file", "mandible", "mandible: no file");

  parts = small(phantomParts("p2"));
  parts[5].fileName = "skull.docx";
  refused(parts, http::status::bad_request, "bad_file", "skull", "is not one of .stl, .obj, .ply");

  parts = small(phantomParts("p2"));
  parts.push_back({"notes", "", "x"});
  refused(parts, http::status::bad_request, "bad_field", "notes", "no such field");

  parts = small(phantomParts("p2"));
  parts[2].data = "furlongs";
  refused(parts, http::status::bad_request, "bad_field", "units", "none of auto, mm, m");

  parts = small(phantomParts("p2"));
  parts.push_back({"oral_cavity", "", "sometimes"});
  refused(parts, http::status::bad_request, "bad_field", "oral_cavity", "none of auto, none");

  // Damaged surfaces: the importer's message names the user's file and the defect.
  parts = phantomParts("p2");
  parts[6].fileName = "broken_jaw.stl";
  parts[6].data = parts[6].data.substr(0, 1000);
  refused(parts, http::status::bad_request, "import_failed", "", "broken_jaw.stl");
  // A small hole is filled (repaired and reported); half the skin missing is not.
  parts = phantomParts("p2");
  parts[4].fileName = "holed_skin.obj";
  {
    std::string& obj = parts[4].data;
    const size_t firstFace = obj.find("\nf ") + 1;
    size_t cut = firstFace + (obj.size() - firstFace) / 2;
    cut = obj.find("\nf ", cut) + 1;
    obj.erase(cut);  // the second half of the triangles
  }
  refused(parts, http::status::bad_request, "import_failed", "", "holed_skin.obj: ");

  // Over the limit (1 MiB here): refused on its declared length, before the body is read.
  {
    const fs::path otherData = data_.string() + "-1MiB";  // a data folder has one server
    test::ServerProcess small1MiB({"--data", otherData.string(), "--no-warm-up", "--max-upload-mb", "1"});
    const std::vector<test::HttpReply> replies =
        test::httpRaw(small1MiB.port(),
                      "POST /api/patients HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: multipart/form-data; "
                      "boundary=B\r\nContent-Length: 2000000\r\n\r\n--B\r\n");
    ASSERT_EQ(replies.size(), 1u);
    EXPECT_EQ(replies[0].result(), http::status::payload_too_large);
    EXPECT_EQ(json::parse(replies[0].body())["error"], "body_too_large");
    EXPECT_FALSE(fs::exists(otherData / "patients"));
    EXPECT_TRUE(!fs::exists(otherData / "imports") || fs::is_empty(otherData / "imports"));
  }

  // A page of another site may not post here.
  refused(small(phantomParts("p2")), http::status::forbidden, "bad_origin", "", "refused",
          "Origin: http://evil.example\r\n");

  EXPECT_EQ(caseIds(server.port()).size(), 6u);  // the built-in cases only
  EXPECT_EQ(test::httpGet(server.port(), "/api/health").result(), http::status::ok);
}

// A closed tetrahedron 4 mm across at `c`, as binary STL, facing outward.
std::string tetrahedronStl(const Eigen::Vector3f& c) {
  const std::array<Eigen::Vector3f, 4> v = {c + Eigen::Vector3f(2, 2, 2), c + Eigen::Vector3f(2, -2, -2),
                                            c + Eigen::Vector3f(-2, 2, -2), c + Eigen::Vector3f(-2, -2, 2)};
  const std::array<std::array<int, 3>, 4> faces = {{{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}}};
  std::string stl(80, ' ');
  const std::uint32_t n = 4;
  stl.append(reinterpret_cast<const char*>(&n), 4);
  for (const auto& f : faces) {
    const Eigen::Vector3f normal = (v[f[1]] - v[f[0]]).cross(v[f[2]] - v[f[0]]).normalized();
    stl.append(reinterpret_cast<const char*>(normal.data()), 12);
    for (int k : f) stl.append(reinterpret_cast<const char*>(v[k].data()), 12);
    stl.append(2, '\0');
  }
  return stl;
}

// The centre of a binary STL's bounding box.
Eigen::Vector3f stlCentre(const std::string& stl) {
  std::uint32_t n = 0;
  std::memcpy(&n, stl.data() + 80, 4);
  Eigen::Vector3f lo = Eigen::Vector3f::Constant(1e9f), hi = -lo;
  for (std::uint32_t t = 0; t < n; ++t)
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector3f p;
      std::memcpy(p.data(), stl.data() + 84 + 50 * t + 12 + 12 * k, 12);
      lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    }
  return 0.5f * (lo + hi);
}

// One rule for importing and opening: what the import accepts opens. A mandible that passes every
// check of its own but lies inside the skull (no tissue to bond to it) and a texture that is no
// image are refused at the import, naming what is wrong, and the id stays free for the good files.
TEST_F(PatientUpload, AnAcceptedImportAlwaysOpensAndARefusedOneFreesItsId) {
  test::ServerProcess server(serverArgs());
  auto refusedWith = [&](std::vector<Part> parts, const std::string& field, const std::string& words) {
    const test::HttpReply reply = upload(server.port(), parts);
    EXPECT_EQ(reply.result(), http::status::bad_request) << reply.body();
    const json error = json::parse(reply.body());
    EXPECT_EQ(error["error"], "import_failed") << reply.body();
    EXPECT_EQ(error.value("field", ""), field) << reply.body();
    EXPECT_NE(error["message"].get<std::string>().find(words), std::string::npos) << reply.body();
    EXPECT_EQ(error["message"].get<std::string>().find(data_.string()), std::string::npos) << reply.body();
    EXPECT_TRUE(importsOnDisk().empty()) << reply.body();
    const std::vector<std::string> ids = caseIds(server.port());
    EXPECT_EQ(std::find(ids.begin(), ids.end(), "p3"), ids.end()) << "a refused import is not listed";
  };
  std::vector<Part> parts = phantomParts("p3");
  parts[6].data = tetrahedronStl(stlCentre(parts[5].data));
  refusedWith(parts, "", "would not open");

  parts = phantomParts("p3");
  parts[8].data = "this is not a picture";
  refusedWith(parts, "texture", "skin.jpg: not a JPEG or PNG image");

  const test::HttpReply good = upload(server.port(), phantomParts("p3"));
  ASSERT_EQ(good.result(), http::status::created) << good.body();
  test::WsTestClient ws(server.port());
  ws.request({{"type", "open"}, {"case", "p3"}});
  std::vector<std::string> phases;
  const json opened = ws.waitFor(
      [&](const json& m) {
        if (m["type"] == "open_progress") phases.push_back(m["phase"]);
        return m["type"] == "opened" || m["type"] == "error";
      },
      180s);
  EXPECT_EQ(opened["type"], "opened") << opened.dump();
}

// Editing an imported patient's landmarks and osteotomies: a landmark moved and the Le Fort I shifted
// 2 mm up rewrite the case, which opens again with its models rebuilt and progress on the way; a
// refused edit leaves the case file as it was; built-in cases cannot be edited; the edit stays.
TEST_F(PatientUpload, EditingLandmarksAndCutsRebuildsTheCaseWithProgress) {
  std::array<double, 3> nasion{};
  {
    test::ServerProcess server(serverArgs());
    ASSERT_EQ(upload(server.port(), phantomParts("edit-me")).result(), http::status::created);
    test::WsTestClient ws(server.port());
    ws.request({{"type", "open"}, {"case", "edit-me"}});
    const json opened = ws.waitFor("opened", 180s);
    EXPECT_TRUE(opened["editable"].get<bool>());
    bool apexNeeded = false;
    for (const json& n : opened["landmarks_needed"])
      if (n["name"] == "upper_incisor_apex") apexNeeded = n["placed"].get<bool>() && n["by"][0] == "le_fort_1";
    EXPECT_TRUE(apexNeeded) << opened["landmarks_needed"].dump();
    EXPECT_TRUE(opened["frame_from_landmarks"].is_null()) << "the phantom has no porions";
    const std::vector<double> n = opened["landmarks_mm"]["nasion"];
    nasion = {n[0], n[1], n[2] + 1.0};
    const std::string before = readFile(data_ / "patients" / "edit-me" / "case.json");

    // Refused: an unknown template. The case file is untouched.
    const json refused = ws.request({{"type", "edit_case"}, {"cuts", {{{"kind", "le_fort_3"}}}}});
    EXPECT_EQ(refused["type"], "error") << refused.dump();
    EXPECT_EQ(refused["error"], "edit_failed");
    EXPECT_NE(refused["message"].get<std::string>().find("le_fort_3"), std::string::npos) << refused.dump();
    EXPECT_EQ(readFile(data_ / "patients" / "edit-me" / "case.json"), before);
    // Refused: a landmark name that would be markup on the page (the import's rule too).
    const json markup = ws.request({{"type", "edit_case"}, {"landmarks", {{"<img src=x>", {1, 2, 3}}}}});
    EXPECT_EQ(markup["type"], "error") << markup.dump();
    EXPECT_NE(markup["message"].get<std::string>().find("a landmark name is 1-64"), std::string::npos) << markup.dump();
    EXPECT_EQ(readFile(data_ / "patients" / "edit-me" / "case.json"), before);

    // Accepted: nasion 1 mm up, Le Fort I 2 mm above its default level (4 mm), BSSO kept.
    ws.send({{"type", "edit_case"},
             {"landmarks", {{"nasion", {nasion[0], nasion[1], nasion[2]}}}},
             {"cuts", {{{"kind", "le_fort_1"}, {"offset_mm", 6.0}}, {{"kind", "bsso"}}}}});
    ws.waitFor("case_edited", 60s);
    std::vector<std::string> phases;
    const json reopened = ws.waitFor(
        [&](const json& m) {
          if (m["type"] == "open_progress") phases.push_back(m["phase"]);
          return m["type"] == "opened";
        },
        180s);
    EXPECT_EQ(phases, (std::vector<std::string>{"mesh", "model"}));
    EXPECT_EQ(reopened["cuts"][0]["offset_mm"], 6.0) << reopened["cuts"].dump();
    EXPECT_EQ(reopened["cuts"][1]["kind"], "bsso");
    EXPECT_NEAR(reopened["landmarks_mm"]["nasion"][2].get<double>(), nasion[2], 1e-9);
    ws.request({{"type", "set_poses"}, {"poses", {{"maxilla", {{"anterior_mm", 2.0}}}}}});
    const json preview = ws.waitFor("preview", 120s);
    EXPECT_TRUE(preview["figures"]["converged"].get<bool>()) << preview.dump();

    test::WsTestClient builtIn(server.port());
    builtIn.request({{"type", "open"}, {"case", "phantom-0"}});
    builtIn.waitFor("opened", 180s);
    const json readOnly = builtIn.request({{"type", "edit_case"}, {"cuts", json::array()}});
    EXPECT_EQ(readOnly["error"], "read_only_case") << readOnly.dump();
  }
  test::ServerProcess restarted(serverArgs());
  test::WsTestClient ws(restarted.port());
  ws.request({{"type", "open"}, {"case", "edit-me"}});
  const json opened = ws.waitFor("opened", 180s);
  EXPECT_EQ(opened["cuts"][0]["offset_mm"], 6.0) << "the edit stays";
  EXPECT_NEAR(opened["landmarks_mm"]["nasion"][2].get<double>(), nasion[2], 1e-9);
}

// A label map instead of the surfaces reaches the engine's label-map import: a map without the
// mandible's label is refused naming the user's file and the label; the fields are checked first.
TEST_F(PatientUpload, ALabelMapIsImportedWithItsLabelNumbers) {
  test::LabelGrid grid;  // a 20 mm box of soft tissue (1) holding a 10 mm box of skull (2)
  grid.spacing = 1.0;
  grid.n = {20, 20, 20};
  grid.labels.assign(8000, 0);
  for (int k = 2; k < 18; ++k)
    for (int j = 2; j < 18; ++j)
      for (int i = 2; i < 18; ++i)
        grid.labels[i + 20 * (j + 20 * k)] = (i > 5 && i < 14 && j > 5 && j < 14 && k > 5 && k < 14) ? 2 : 1;
  const fs::path map = data_.string() + "-head.nii.gz";
  test::writeNiftiLabels(grid, map.string());
  const std::string bytes = readFile(map);
  fs::remove(map);
  test::ServerProcess server(serverArgs());
  auto labelled = [&](const std::string& tissue, const std::string& skull, const std::string& mandible) {
    return std::vector<Part>{{"id", "", "from-labels"},
                             {"label_map", "head.nii.gz", bytes},
                             {"tissue_labels", "", tissue},
                             {"skull_labels", "", skull},
                             {"mandible_labels", "", mandible}};
  };
  const test::HttpReply missing = upload(server.port(), labelled("1", "2", "3"));
  EXPECT_EQ(missing.result(), http::status::bad_request) << missing.body();
  const json error = json::parse(missing.body());
  EXPECT_EQ(error["error"], "import_failed");
  const std::string message = error["message"];
  EXPECT_NE(message.find("head.nii.gz"), std::string::npos) << message;
  EXPECT_NE(message.find("label 3"), std::string::npos) << message;
  EXPECT_EQ(message.find(data_.string()), std::string::npos) << message;

  const test::HttpReply badNumber = upload(server.port(), labelled("1", "two", "3"));
  EXPECT_EQ(json::parse(badNumber.body())["field"], "skull_labels") << badNumber.body();
  const test::HttpReply noLabels = upload(server.port(), labelled("1", "2", ""));
  EXPECT_EQ(json::parse(noLabels.body())["field"], "mandible_labels") << noLabels.body();
  std::vector<Part> both = labelled("1", "2", "3");
  both.push_back(file("skin", "skin.obj"));
  const test::HttpReply twice = upload(server.port(), both);
  EXPECT_NE(json::parse(twice.body())["message"].get<std::string>().find("not both"), std::string::npos)
      << twice.body();
  EXPECT_TRUE(importsOnDisk().empty());
}

}  // namespace
}  // namespace orthosim
