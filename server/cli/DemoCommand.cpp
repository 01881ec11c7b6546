// `orthosim demo`: the built-in demo patient, no data needed. Writes the phantom (class I head:
// skin with texture, skull, mandible, oral cavity, landmarks) as a surface-based case with a Le
// Fort I and a sagittal split and a 5 mm maxillary advancement planned, then solves it exactly as
// `orthosim solve` would (coarse model, built tissue cached in the output folder).
#include <filesystem>
#include <iostream>
#include <memory>

#include "cli/CommandLine.hpp"
#include "cli/CommandRun.hpp"
#include "cli/Commands.hpp"
#include "phantom/PhantomCase.hpp"

namespace orthosim::cli {
namespace fs = std::filesystem;

int runDemo(const std::string& outDir) {
  const std::string casePath = writePhantomCase(0, (fs::path(outDir) / "case").string());
  std::cout << "demo patient written to " << casePath << " (phantom class I); edit its plan and run "
            << "`orthosim solve` on it\n";
  SolveOptions options;
  options.cacheDir = (fs::path(outDir) / "cache").string();
  return runSolve(casePath, (fs::path(outDir) / "result").string(), options);
}

void addDemoCommand(CLI::App& parent) {
  auto out = std::make_shared<std::string>("orthosim-demo");
  auto* demo = parent.add_subcommand("demo", "Write the built-in demo scene and solve it (no data needed)");
  demo->add_option("--out", *out, "Output folder (scene/ and result/ inside)");
  runWhenChosen(*demo, [out] { return runDemo(*out); });
}

}  // namespace orthosim::cli
