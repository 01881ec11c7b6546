#include "system/FolderInMessage.hpp"

#include <gtest/gtest.h>

namespace orthosim {
namespace {

TEST(FolderInMessage, RemovesEveryOccurrenceOfTheFolder) {
  EXPECT_EQ(withoutFolder("/tmp/stage-1/skin.obj: not closed; see /tmp/stage-1/skull.stl", "/tmp/stage-1/"),
            "skin.obj: not closed; see skull.stl");
}

TEST(FolderInMessage, ReplacesTheFolderByTheUsersWords) {
  EXPECT_EQ(withoutFolder("/srv/scan-7 holds no DICOM series", "/srv/scan-7", "the scan"),
            "the scan holds no DICOM series");
}

TEST(FolderInMessage, ReplacementThatContainsTheFolderIsNotReplacedAgain) {
  EXPECT_EQ(withoutFolder("a b a", "a", "aa"), "aa b aa");
}

TEST(FolderInMessage, EmptyFolderLeavesTheMessage) { EXPECT_EQ(withoutFolder("/x/y", ""), "/x/y"); }

}  // namespace
}  // namespace orthosim
