#include "PackageLists.hpp"

#include <algorithm>
#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>

namespace orthosim::test {
namespace {

std::vector<std::string> words(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

std::vector<std::string> lines(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> out;
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

// Joins `\`-continued lines, so that one instruction is one line.
std::vector<std::string> instructions(const std::string& text) {
  std::vector<std::string> out;
  std::string current;
  for (const std::string& l : lines(text)) {
    if (!l.empty() && l.back() == '\\') {
      current += l.substr(0, l.size() - 1) + " ";
      continue;
    }
    out.push_back(current + l);
    current.clear();
  }
  if (!current.empty()) out.push_back(current);
  return out;
}

}  // namespace

std::vector<std::string> setupScriptPackages(const std::string& script) {
  // Comments first: they may hold parentheses of their own.
  std::string code;
  for (const std::string& l : lines(script)) code += l.substr(0, l.find('#')) + "\n";
  const size_t start = code.find("PACKAGES=(");
  if (start == std::string::npos) throw std::runtime_error("setup script: no PACKAGES=( ... ) array");
  const size_t end = code.find(')', start);
  if (end == std::string::npos) throw std::runtime_error("setup script: PACKAGES=( is not closed");
  return words(code.substr(start + 10, end - start - 10));
}

DockerfilePackages parseDockerfile(const std::string& dockerfile) {
  DockerfilePackages d;
  const std::regex mapLine(R"(^#\s+pkg\s+(\S+)\s+->\s+([^(]*).*$)");
  const std::regex arg(R"re(^\s*ARG\s+RUNTIME_PACKAGES="([^"]*)")re");
  for (const std::string& l : lines(dockerfile)) {
    std::smatch m;
    if (std::regex_match(l, m, mapLine)) {
      std::vector<std::string> runtime = words(m[2]);
      runtime.erase(std::remove(runtime.begin(), runtime.end(), "-"), runtime.end());
      if (!d.runtimeOf.emplace(m[1], runtime).second) d.duplicates.push_back(m[1]);
    } else if (std::regex_search(l, m, arg)) {
      d.runtimePackages = words(m[1]);
    }
  }
  std::string stage;
  const std::regex from(R"(^\s*FROM\s+\S+(\s+AS\s+(\S+))?)", std::regex::icase);
  for (const std::string& ins : instructions(dockerfile)) {
    std::smatch m;
    if (std::regex_search(ins, m, from)) stage = m[2];
    if (ins.rfind("#", 0) == 0) continue;
    if (stage == "build" && ins.find("bash scripts/setup-deps.sh") != std::string::npos) d.buildRunsSetupScript = true;
    if (ins.find("apt-get install") == std::string::npos) continue;
    if (stage == "runtime" && ins.find("$RUNTIME_PACKAGES") != std::string::npos)
      d.runtimeInstallsList = true;
    else
      d.otherInstalls.push_back(ins);
  }
  return d;
}

std::vector<std::string> packageDrift(const std::vector<std::string>& setup, const DockerfilePackages& d) {
  std::vector<std::string> problems;
  const std::set<std::string> setupSet(setup.begin(), setup.end());
  for (const std::string& p : setup)
    if (!d.runtimeOf.count(p))
      problems.push_back(p + ": installed by scripts/setup-deps.sh but missing from docker/Dockerfile's package map");
  for (const auto& [p, runtime] : d.runtimeOf)
    if (!setupSet.count(p))
      problems.push_back(p + ": in docker/Dockerfile's package map but not installed by scripts/setup-deps.sh");
  for (const std::string& p : d.duplicates) problems.push_back(p + ": named twice in docker/Dockerfile's package map");

  std::set<std::string> needed;
  for (const auto& [p, runtime] : d.runtimeOf) needed.insert(runtime.begin(), runtime.end());
  const std::set<std::string> listed(d.runtimePackages.begin(), d.runtimePackages.end());
  for (const std::string& p : needed)
    if (!listed.count(p)) problems.push_back(p + ": needed by the package map but not in RUNTIME_PACKAGES");
  for (const std::string& p : listed)
    if (!needed.count(p)) problems.push_back(p + ": in RUNTIME_PACKAGES but no package of the map needs it");

  if (!d.buildRunsSetupScript) problems.push_back("the build stage does not run bash scripts/setup-deps.sh");
  if (!d.runtimeInstallsList) problems.push_back("the runtime stage does not apt-get install $RUNTIME_PACKAGES");
  for (const std::string& ins : d.otherInstalls) problems.push_back("an apt-get install outside the two lists: " + ins);
  return problems;
}

}  // namespace orthosim::test
