// docker/Dockerfile and scripts/setup-deps.sh must not drift apart: the build stage runs the setup
// script, every package the script installs is in the Dockerfile's package map, and the runtime
// stage installs exactly what the map says the binary needs. The checker itself is shown to catch
// a package added to one file only.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "PackageLists.hpp"

namespace orthosim::test {
namespace {

std::string readSource(const std::string& relative) {
  std::ifstream in(std::string(ORTHOSIM_SOURCE_DIR) + "/" + relative);
  if (!in) throw std::runtime_error(relative + ": cannot open");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string setupScript() { return readSource("scripts/setup-deps.sh"); }
std::string dockerfile() { return readSource("docker/Dockerfile"); }

std::vector<std::string> drift(const std::string& script, const std::string& docker) {
  return packageDrift(setupScriptPackages(script), parseDockerfile(docker));
}

bool mentions(const std::vector<std::string>& problems, const std::string& what) {
  for (const std::string& p : problems)
    if (p.find(what) != std::string::npos) return true;
  return false;
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  if (at == std::string::npos) throw std::runtime_error("'" + from + "' not found");
  return text.replace(at, from.size(), to);
}

TEST(DockerPackages, DockerfileMatchesSetupScript) {
  const std::vector<std::string> setup = setupScriptPackages(setupScript());
  EXPECT_GE(setup.size(), 10u);  // the parser found the real list, not an empty one
  const DockerfilePackages docker = parseDockerfile(dockerfile());
  EXPECT_GE(docker.runtimePackages.size(), 5u);
  const std::vector<std::string> problems = packageDrift(setup, docker);
  for (const std::string& p : problems) ADD_FAILURE() << p;
}

TEST(DockerPackages, ParsesThePackagesArrayWithoutComments) {
  const std::string script = "X=1\nPACKAGES=(\n  a b   # comment (words)\n  c\n)\nfor p in x; do :; done\n";
  EXPECT_EQ(setupScriptPackages(script), (std::vector<std::string>{"a", "b", "c"}));
  EXPECT_THROW(setupScriptPackages("echo no list\n"), std::runtime_error);
}

TEST(DockerPackages, CatchesAPackageAddedToTheSetupScriptOnly) {
  const std::string script = replaced(setupScript(), "PACKAGES=(", "PACKAGES=(\n  libexample-drift-dev");
  EXPECT_TRUE(mentions(drift(script, dockerfile()), "libexample-drift-dev: installed by scripts/setup-deps.sh"));
}

TEST(DockerPackages, CatchesAPackageAddedToTheDockerfileOnly) {
  const std::string mapped =
      replaced(dockerfile(), "#   pkg cmake", "#   pkg libexample-drift-dev -> libexample-drift1\n#   pkg cmake");
  const std::string docker = replaced(mapped, "ARG RUNTIME_PACKAGES=\"", "ARG RUNTIME_PACKAGES=\"libexample-drift1 ");
  EXPECT_TRUE(
      mentions(drift(setupScript(), docker), "libexample-drift-dev: in docker/Dockerfile's package map but not"));
  // A runtime package that no map line asks for, and one a map line asks for but is not installed.
  const std::string extra = replaced(dockerfile(), "ARG RUNTIME_PACKAGES=\"", "ARG RUNTIME_PACKAGES=\"curl ");
  EXPECT_TRUE(mentions(drift(setupScript(), extra), "curl: in RUNTIME_PACKAGES but no package"));
  const std::string missing = replaced(dockerfile(), " libassimp5 ", " ");
  EXPECT_TRUE(mentions(drift(setupScript(), missing), "libassimp5: needed by the package map"));
}

TEST(DockerPackages, CatchesAnInstallOutsideTheLists) {
  const std::string docker =
      replaced(dockerfile(), "COPY . .", "RUN apt-get install -y libexample-drift-dev\nCOPY . .");
  EXPECT_TRUE(mentions(drift(setupScript(), docker), "apt-get install outside the two lists"));
  const std::string noScript = replaced(dockerfile(), "RUN bash scripts/setup-deps.sh", "RUN true");
  EXPECT_TRUE(mentions(drift(setupScript(), noScript), "does not run bash scripts/setup-deps.sh"));
}

}  // namespace
}  // namespace orthosim::test
