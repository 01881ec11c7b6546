#pragma once
// The package lists of scripts/setup-deps.sh and docker/Dockerfile, parsed from their text, and
// the ways they can drift apart (test DockerPackages). Test-only: nothing in orthosim reads them.
#include <map>
#include <string>
#include <vector>

namespace orthosim::test {

// The words of the bash array `PACKAGES=( ... )`, comments left out. Throws std::runtime_error
// when the text has no such array.
std::vector<std::string> setupScriptPackages(const std::string& script);

struct DockerfilePackages {
  // "#   pkg NAME -> RUNTIME... (why)" lines: each setup package and the runtime packages it needs
  // ("-": none). A name given twice is kept in `duplicates`.
  std::map<std::string, std::vector<std::string>> runtimeOf;
  std::vector<std::string> duplicates;
  std::vector<std::string> runtimePackages;  // ARG RUNTIME_PACKAGES="..."
  bool buildRunsSetupScript = false;         // the build stage runs `bash scripts/setup-deps.sh`
  bool runtimeInstallsList = false;          // the runtime stage's apt-get install names $RUNTIME_PACKAGES
  std::vector<std::string> otherInstalls;    // any other apt-get install line, in either stage
};

DockerfilePackages parseDockerfile(const std::string& dockerfile);

// Every way the two files disagree, one line each naming the package; empty when they agree.
std::vector<std::string> packageDrift(const std::vector<std::string>& setupPackages, const DockerfilePackages& docker);

}  // namespace orthosim::test
