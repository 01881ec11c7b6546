#pragma once
// Sub-commands of the `orthosim` executable.
#include <string>
#include <vector>

namespace orthosim::cli {

// Exit codes: 0 converged, 1 bad input, 2 solve did not converge (outputs hold the last good state).
int runSolve(const std::string& scenePath, const std::string& outDir);

// Writes the built-in demo scene under outDir/scene and solves it into outDir/result.
int runDemo(const std::string& outDir);

struct BenchOptions {
  std::vector<int> tetCounts{2000, 20000, 100000};
  int repeats = 5;
  std::string jsonPath;  // optional machine-readable copy of the table
};
int runBench(const BenchOptions& options);

}  // namespace orthosim::cli
