#pragma once
// What the import tests assert of every refused import: an error naming the defect, and nothing
// left behind (no case folder with a case file, no half-written ".importing-" folder beside it).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "scene/CaseImport.hpp"

namespace orthosim::test {

// The message of a failed import into `out`; fails the test when it succeeds or leaves anything.
inline std::string importRefusal(const CaseImportInput& in, const std::filesystem::path& out) {
  try {
    importCase(in, out.string());
    ADD_FAILURE() << "imported";
  } catch (const CaseImportError& e) {
    // `out` may exist (an import refused because it does): it must not hold a case.
    EXPECT_FALSE(std::filesystem::is_regular_file(out / "case.json")) << "no half-built case";
    for (const auto& entry : std::filesystem::directory_iterator(out.parent_path()))
      EXPECT_EQ(entry.path().filename().string().find(".importing-"), std::string::npos) << entry.path();
    return e.what();
  }
  return {};
}

}  // namespace orthosim::test
