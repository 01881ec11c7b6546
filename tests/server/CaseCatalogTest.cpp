// What the server offers: the phantom's variants, the ArtiSynth face when its shipped folder is
// there, and case folders with valid names and case files.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "cases/CaseCatalog.hpp"

namespace orthosim::server {
namespace {
namespace fs = std::filesystem;

TEST(CaseCatalog, TheShippedFaceIsListedOnlyWhereItIs) {
  const std::vector<CaseEntry> phantom = builtInCases();
  ASSERT_FALSE(phantom.empty());
  for (const CaseEntry& c : phantom) EXPECT_EQ(c.source, "phantom");
  EXPECT_EQ(builtInCases(fs::temp_directory_path() / "no-such-orthosim-cases").size(), phantom.size());

  const std::vector<CaseEntry> all = builtInCases(ORTHOSIM_CASES_DIR);
  ASSERT_EQ(all.size(), phantom.size() + 1);
  const CaseEntry& face = all.back();
  EXPECT_EQ(face.id, kArtisynthFaceId);
  EXPECT_EQ(face.source, "artisynth");
  EXPECT_TRUE(fs::is_regular_file(face.folder / "LICENSE_ArtiSynth_Models.txt")) << "its licence travels with it";
  EXPECT_TRUE(fs::is_regular_file(face.folder / "README.md")) << "and its citations";
  const nlohmann::json listed = casesJson(all);
  EXPECT_EQ(listed["cases"].back()["id"], "artisynth-face");
  EXPECT_FALSE(listed["cases"].back().contains("variant"));
}

TEST(CaseCatalog, FolderCasesSkipBadNamesAndFilesAndSayWhy) {
  const fs::path dir = fs::temp_directory_path() / ("orthosim-catalog-" + std::to_string(::getpid()));
  fs::create_directories(dir / "Bad Name");
  std::ofstream(dir / "Bad Name" / "case.json") << "{}";
  fs::create_directories(dir / "torn");
  std::ofstream(dir / "torn" / "case.json") << "{\"tissue\": ";
  fs::create_directories(dir / "empty");  // no case.json: not a case, nothing to say
  std::vector<std::string> skipped;
  EXPECT_TRUE(folderCases(dir, &skipped).empty());
  EXPECT_EQ(skipped.size(), 2u);
  for (const std::string& s : skipped)
    EXPECT_TRUE(s.find("Bad Name") != std::string::npos || s.find("torn") != std::string::npos) << s;
  fs::remove_all(dir);
  EXPECT_THROW(folderCases(dir), std::runtime_error);
}

}  // namespace
}  // namespace orthosim::server
