// Cases another replica adds to the shared data folder (cases/CaseLibrary::discoverWith): asked for
// by the list and by a lookup of an unknown id, told which ids are known already, and joined to
// the catalog once.
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <set>
#include <string>
#include <vector>

#include "cases/CaseLibrary.hpp"

namespace orthosim::server {
namespace {

TEST(CaseLibraryDiscovery, CasesAddedElsewhereJoinTheListAndAreFound) {
  CaseLibrary library(builtInCases(), "/nonexistent-data-folder");
  std::vector<CaseEntry> onDisk;
  int asked = 0;
  std::set<std::string> knownWhenAsked;
  library.discoverWith([&](const std::function<bool(const std::string&)>& known) {
    ++asked;
    std::vector<CaseEntry> found;
    for (const CaseEntry& c : onDisk) {
      if (known(c.id)) knownWhenAsked.insert(c.id);
      if (!known(c.id)) found.push_back(c);
    }
    return found;
  });
  EXPECT_FALSE(library.find("jane").has_value());
  EXPECT_EQ(asked, 1) << "an unknown id is looked for on disk";
  EXPECT_TRUE(library.find("phantom-0").has_value());
  EXPECT_EQ(asked, 1) << "a known id is not";

  CaseEntry jane;
  jane.id = "jane";
  jane.source = "import";
  onDisk.push_back(jane);  // imported through another replica
  ASSERT_TRUE(library.find("jane").has_value());
  EXPECT_EQ(library.find("jane")->source, "import");
  const std::vector<CaseEntry> list = library.catalog();
  EXPECT_EQ(std::count_if(list.begin(), list.end(), [](const CaseEntry& c) { return c.id == "jane"; }), 1);
  EXPECT_EQ(knownWhenAsked.count("jane"), 1u) << "the list told the discovery that jane is known already";
  EXPECT_THROW(library.add(jane), std::invalid_argument) << "joined once";
}

}  // namespace
}  // namespace orthosim::server
