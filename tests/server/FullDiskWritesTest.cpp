// A full disk during a write: a probe left 0-byte temporary files beside case files (case edits)
// and tissue-cache entries while the server ran. Each write now fails with the system's reason and
// leaves the old file and no temporary one. Needs a small tmpfs (mount works as root; skipped
// otherwise, failed under CI=true).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "TestData.hpp"
#include "cases/CaseEdit.hpp"
#include "meshing/BoxMesh.hpp"
#include "phantom/PhantomCase.hpp"
#include "scene/CaseFile.hpp"
#include "scene/TissueCache.hpp"
#include "session/PlanStore.hpp"
#include "session/ProtocolError.hpp"
#include "system/AtomicFile.hpp"

namespace orthosim::server {
namespace {
namespace fs = std::filesystem;

std::string readFile(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

class FullDisk : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("orthosim_full_disk_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    if (std::system(("mount -t tmpfs -o size=64m tmpfs " + dir_.string() + " 2>/dev/null").c_str()) != 0) {
      fs::remove_all(dir_);
      SKIP_OR_FAIL_FOR_MISSING_PREREQUISITE(
          "cannot mount a small tmpfs here (not root): the full-disk path is not exercised");
    }
    mounted_ = true;
  }
  void TearDown() override {
    if (mounted_) (void)std::system(("umount " + dir_.string()).c_str());
    fs::remove_all(dir_);
  }
  // Takes every free byte: the next write of any size fails with ENOSPC.
  void fill() {
    std::ofstream filler(dir_ / "filler", std::ios::binary);
    const std::string chunk(64 * 1024, 'x');
    while (filler.write(chunk.data(), static_cast<std::streamsize>(chunk.size()))) {
    }
    filler.close();
    std::ofstream(dir_ / "filler-small", std::ios::binary).write("x", 1);  // the last page's bytes
    std::ofstream probe(dir_ / "probe", std::ios::binary);
    probe << std::string(8192, 'y');
    probe.close();
    ASSERT_FALSE(probe) << "the disk is not full";
    fs::remove(dir_ / "probe");
  }
  // Every file under the disk whose name holds a temporary marker.
  std::vector<std::string> temporaries() const {
    std::vector<std::string> found;
    for (const fs::directory_entry& e : fs::recursive_directory_iterator(dir_)) {
      const std::string name = e.path().filename().string();
      for (const char* marker : {".tmp", ".editing-", ".writing-", ".part-"})
        if (name.find(marker) != std::string::npos) found.push_back(e.path().string());
    }
    return found;
  }
  fs::path dir_;
  bool mounted_ = false;
};

TEST_F(FullDisk, ACaseEditFailsWithTheReasonAndLeavesTheCase) {
  const fs::path caseFile = writePhantomCase(0, (dir_ / "patients" / "jane").string());
  const CaseSpec spec = loadCaseFile(caseFile.string());
  const std::string before = readFile(caseFile);
  fill();
  CaseEdit edit;
  edit.landmarks["upper_incisor_apex"] = spec.landmarks.at("upper_incisor_apex") + spec.frame.superior;
  try {
    applyCaseEdit(caseFile, edit);
    FAIL() << "edited on a full disk";
  } catch (const CaseEditError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("No space left on device"), std::string::npos) << message;
    EXPECT_EQ(message.find(dir_.string()), std::string::npos) << "no server path for the client: " << message;
  }
  EXPECT_EQ(readFile(caseFile), before);
  EXPECT_EQ(temporaries(), std::vector<std::string>{});
}

TEST_F(FullDisk, APlanSaveFailsWithTheReasonAndKeepsTheSavedPlan) {
  PlanStore plans(dir_ / "plans");
  plans.save("phantom-0", "setback", {{"poses", {{"maxilla", {{"anterior_mm", -2}}}}}});
  const std::string before = readFile(dir_ / "plans" / "phantom-0" / "setback.json");
  fill();
  const nlohmann::json bigger = {{"poses", {{"maxilla", {{"anterior_mm", 3}}}}}, {"note", std::string(20000, 'n')}};
  try {
    plans.save("phantom-0", "setback", bigger, /*replace=*/true);
    FAIL() << "saved on a full disk";
  } catch (const ProtocolError& e) {
    EXPECT_EQ(e.code, "save_failed");
    EXPECT_EQ(e.path, "/name");
    const std::string message = e.what();
    EXPECT_NE(message.find("No space left on device"), std::string::npos) << message;
    EXPECT_EQ(message.find(dir_.string()), std::string::npos) << message;
  }
  EXPECT_EQ(readFile(dir_ / "plans" / "phantom-0" / "setback.json"), before);
  EXPECT_EQ(temporaries(), std::vector<std::string>{});
}

TEST_F(FullDisk, ATissueCacheWriteFailsWithTheReasonAndLeavesNoEntry) {
  CaseTissue t;
  t.mesh = makeBoxMesh(BoxSpec{Eigen::Vector3d(10, 8, 6), Eigen::Vector3i(20, 20, 20)});
  t.boneNodes = {{0, 1, 2}};
  fs::create_directories(dir_ / "cache");
  fill();
  const fs::path entry = dir_ / "cache" / "0123abcd.tissue";
  try {
    writeTissueCache(entry.string(), t);
    FAIL() << "wrote the cache on a full disk";
  } catch (const AtomicFileError& e) {
    EXPECT_EQ(e.reason(), "No space left on device") << e.what();
  }
  EXPECT_FALSE(fs::exists(entry));
  EXPECT_EQ(temporaries(), std::vector<std::string>{});
}

}  // namespace
}  // namespace orthosim::server
