// A file written beside its target and renamed over it: the old content stays until the new one is
// complete, and a write that cannot happen says where and leaves nothing behind.
#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "system/AtomicFile.hpp"

namespace orthosim {
namespace {
namespace fs = std::filesystem;

std::string read(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(AtomicFile, ReplacesTheWholeFileAndLeavesNoTemporary) {
  const fs::path dir = fs::temp_directory_path() / ("orthosim_atomic_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  writeFileAtomically(dir / "a.json", "first\n");
  writeFileAtomically(dir / "a.json", "second\n");
  EXPECT_EQ(read(dir / "a.json"), "second\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1) << "no temporary file left";
  fs::remove_all(dir);
}

TEST(AtomicFile, AWriteThatCannotHappenNamesThePath) {
  const fs::path missing = fs::temp_directory_path() / "orthosim_no_such_dir" / "a.json";
  try {
    writeFileAtomically(missing, "x");
    FAIL() << "wrote into a folder that does not exist";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("orthosim_no_such_dir"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("cannot write"), std::string::npos) << e.what();
  }
}

// A writer left by an exception (a serializer that throws halfway) takes its temporary file along.
TEST(AtomicFile, AnExceptionBeforeCommitLeavesNoTemporary) {
  const fs::path dir = fs::temp_directory_path() / ("orthosim_atomic_throw_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  writeFileAtomically(dir / "a.json", "old\n");
  try {
    AtomicFile file(dir / "a.json");
    file.out() << "half";
    EXPECT_TRUE(fs::exists(file.temporaryPath()));
    throw std::runtime_error("the serializer failed");
  } catch (const std::runtime_error&) {
  }
  EXPECT_THROW(writeFileAtomicallyWith(dir / "b.obj",
                                       [](const fs::path& tmp) {
                                         EXPECT_EQ(tmp.extension(), ".obj") << "the exporter's format";
                                         std::ofstream(tmp) << "v 0 0 0\n";
                                         throw std::runtime_error("the exporter failed");
                                       }),
               std::runtime_error);
  EXPECT_EQ(read(dir / "a.json"), "old\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1) << "no temporary file left";
  fs::remove_all(dir);
}

// A rename that fails (the target is a folder) removes the temporary file it would have renamed.
TEST(AtomicFile, AFailedRenameLeavesNoTemporary) {
  const fs::path dir = fs::temp_directory_path() / ("orthosim_atomic_rename_" + std::to_string(::getpid()));
  fs::create_directories(dir / "a.json" / "inside");
  try {
    writeFileAtomically(dir / "a.json", "x");
    FAIL() << "renamed over a folder";
  } catch (const AtomicFileError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot rename"), std::string::npos) << e.what();
  }
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1) << "no temporary file left";
  fs::remove_all(dir);
}

}  // namespace
}  // namespace orthosim
