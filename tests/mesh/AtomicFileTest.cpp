// A file written beside its target and renamed over it: the old content stays until the new one is
// complete, and a write that cannot happen says where and leaves nothing behind.
#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <sstream>

#include "mesh/AtomicFile.hpp"

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

}  // namespace
}  // namespace orthosim
