// The Dockerfile's runtime stage must hold every shared library the built orthosim loads directly:
// each NEEDED entry of the binary, resolved by the dynamic loader on this (Debian 12) machine, must
// belong to a package in RUNTIME_PACKAGES or to the base image. Libraries those load in turn come
// with the packages' own dependencies. Skips where dpkg or readelf is missing (not Debian); fails
// so under CI=true (Debian 12, readelf from build-essential's binutils).
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <regex>
#include <set>
#include <sstream>

#include "PackageLists.hpp"
#include "TestData.hpp"

namespace orthosim::test {
namespace {

std::string output(const std::string& command) {
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  if (!pipe) return {};
  std::string out;
  char buf[4096];
  for (size_t n; (n = fread(buf, 1, sizeof buf, pipe.get())) > 0;) out.append(buf, n);
  return out;
}

// The package owning `path` ("" when none): dpkg knows a library by the path it was installed
// under, which with the merged /usr may be the /lib or the /usr/lib spelling.
std::string owner(const std::filesystem::path& path) {
  std::vector<std::string> candidates{path.string(), std::filesystem::weakly_canonical(path).string()};
  for (const std::string& c : std::vector<std::string>(candidates)) {
    if (c.rfind("/usr/", 0) == 0)
      candidates.push_back(c.substr(4));
    else
      candidates.push_back("/usr" + c);
  }
  for (const std::string& c : candidates) {
    const std::string line = output("dpkg-query -S '" + c + "' 2>/dev/null");
    const size_t colon = line.find(':');
    if (colon != std::string::npos && line.find(c) != std::string::npos) return line.substr(0, colon);
  }
  return {};
}

TEST(DockerRuntime, ListedPackagesHoldEveryLibraryTheBinaryNeeds) {
  if (std::system("command -v dpkg-query >/dev/null 2>&1 && command -v readelf >/dev/null 2>&1") != 0)
    SKIP_OR_FAIL_FOR_MISSING_PREREQUISITE("dpkg-query or readelf not available (not Debian, or binutils missing)");
  std::ifstream in(std::string(ORTHOSIM_SOURCE_DIR) + "/docker/Dockerfile");
  std::ostringstream text;
  text << in.rdbuf();
  const DockerfilePackages docker = parseDockerfile(text.str());
  std::set<std::string> allowed(docker.runtimePackages.begin(), docker.runtimePackages.end());
  for (const char* base : {"libc6", "libstdc++6", "libgcc-s1"}) allowed.insert(base);  // in debian:12 itself

  std::map<std::string, std::string> resolved;  // soname -> path, as the loader finds it
  const std::regex lddLine(R"(^\s*(\S+)\s+=>\s+(\S+))");
  std::istringstream ldd(output(std::string("ldd ") + ORTHOSIM_CLI));
  for (std::string l; std::getline(ldd, l);)
    if (std::smatch m; std::regex_search(l, m, lddLine)) resolved[m[1]] = m[2];

  const std::regex neededLine(R"(\(NEEDED\).*\[(\S+)\])");
  std::istringstream elf(output(std::string("readelf -d ") + ORTHOSIM_CLI));
  int needed = 0;
  for (std::string l; std::getline(elf, l);) {
    std::smatch m;
    if (!std::regex_search(l, m, neededLine)) continue;
    ++needed;
    const std::string soname = m[1];
    ASSERT_TRUE(resolved.count(soname)) << soname << ": not found by ldd";
    const std::string package = owner(resolved[soname]);
    EXPECT_FALSE(package.empty()) << soname << " (" << resolved[soname] << "): no Debian package owns it";
    EXPECT_TRUE(package.empty() || allowed.count(package))
        << soname << " comes from " << package << ", which docker/Dockerfile's RUNTIME_PACKAGES does not install";
  }
  EXPECT_GE(needed, 5);  // the binary was read
}

}  // namespace
}  // namespace orthosim::test
