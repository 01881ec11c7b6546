#pragma once
// Tests and the data they read. Two kinds of missing data:
//  - data the repository ships (tests/data/...) or the build produces: a developer's partial tree
//    may lack it, so the test skips, but under CI=true (environment variable) it fails, because
//    there missing data means a broken checkout or build and a skip would hide it;
//  - data only in ../shared (the ArtiSynth face, not in the repository): the test always skips,
//    saying exactly which files are missing, since CI's clone may not have ../shared.
// A tool or permission the machine lacks (readelf, mounting a tmpfs) follows the first rule.
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <initializer_list>
#include <string>

namespace orthosim::test {

// CI=true in the environment (as GitHub Actions, GitLab CI and most CI services set it).
inline bool runningInCi() {
  const char* ci = std::getenv("CI");
  return ci != nullptr && std::strcmp(ci, "true") == 0;
}

// "" when every file exists, otherwise "missing: a, b" naming each missing file.
inline std::string missingFiles(std::initializer_list<std::filesystem::path> files) {
  std::string missing;
  for (const std::filesystem::path& f : files)
    if (!std::filesystem::exists(f)) missing += (missing.empty() ? "missing: " : ", ") + f.string();
  return missing;
}

}  // namespace orthosim::test

// For data the repository ships or the build produces: skips the test saying what is missing,
// or fails it under CI=true. Returns from the test body like GTEST_SKIP.
#define SKIP_OR_FAIL_FOR_MISSING_DATA(what)                                            \
  do {                                                                                 \
    if (::orthosim::test::runningInCi()) {                                             \
      GTEST_FAIL() << (what)                                                           \
                   << " (CI=true: data the repository ships or the build produces is " \
                      "never skipped there)";                                          \
    } else {                                                                           \
      GTEST_SKIP() << (what);                                                          \
    }                                                                                  \
  } while (0)

// For a tool or permission the test needs from the machine, which CI provides (Debian 12 with the
// packages of scripts/setup-deps.sh, run as root): skips the test saying what is missing, or fails
// it under CI=true, where a skip would hide a broken setup. Returns from the test body like GTEST_SKIP.
#define SKIP_OR_FAIL_FOR_MISSING_PREREQUISITE(what)                                                     \
  do {                                                                                                  \
    if (::orthosim::test::runningInCi()) {                                                              \
      GTEST_FAIL() << (what) << " (CI=true: the CI machine provides it, so it is never skipped there)"; \
    } else {                                                                                            \
      GTEST_SKIP() << (what);                                                                           \
    }                                                                                                   \
  } while (0)

// For data only in ../shared: skips (also under CI=true) when a file is missing, naming each one.
#define SKIP_WITHOUT_SHARED_DATA(...)                                                        \
  do {                                                                                       \
    const std::string orthosimMissing_ = ::orthosim::test::missingFiles({__VA_ARGS__});      \
    if (!orthosimMissing_.empty())                                                           \
      GTEST_SKIP() << "shared data (../shared, not in the repository) " << orthosimMissing_; \
  } while (0)
