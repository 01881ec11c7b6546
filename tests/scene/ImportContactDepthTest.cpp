// An imported patient's lips and cheeks slide on the teeth, the floor of the mouth does not: the
// import writes the contact depth limit the phantom uses (docs/scene-format.md, importing a
// patient), and the case it writes reads it back.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "phantom/PhantomCase.hpp"
#include "scene/CaseFile.hpp"
#include "scene/CaseImport.hpp"

namespace orthosim {
namespace {
namespace fs = std::filesystem;

TEST(ImportContactDepth, TheImportedCaseLimitsContactToTheLipsAndCheeksAsThePhantomDoes) {
  const fs::path dir = fs::temp_directory_path() / ("orthosim_import_depth_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const CaseSpec phantom = loadCaseFile(writePhantomCase(0, (dir / "export").string()));
  CaseImportInput in;
  in.skin = (dir / "export" / "skin.obj").string();
  in.skull = (dir / "export" / "skull.stl").string();
  in.mandible = (dir / "export" / "mandible.stl").string();
  in.landmarks = (dir / "export" / "landmarks.json").string();
  in.cuts = {"le_fort_1", "bsso"};
  const CaseImportReport report = importCase(in, (dir / "patient").string());

  nlohmann::json written;
  std::ifstream(report.caseFile) >> written;
  ASSERT_EQ(written["contact"].size(), 1u) << written["contact"].dump();
  EXPECT_EQ(written["contact"][0]["max_depth_mm"], 30) << written["contact"].dump();
  const CaseSpec spec = loadCaseFile(report.caseFile);
  ASSERT_EQ(spec.contacts.size(), 1u);
  ASSERT_EQ(phantom.contacts.size(), 1u);
  EXPECT_EQ(spec.contacts[0].maxDepthMm, phantom.contacts[0].maxDepthMm);
  EXPECT_EQ(spec.contacts[0].rangeMm, phantom.contacts[0].rangeMm);
  EXPECT_EQ(spec.contacts[0].bones, phantom.contacts[0].bones);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace orthosim
