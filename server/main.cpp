// orthosim: soft-tissue prediction for orthognathic surgery planning.
#include <CLI/CLI.hpp>
#include <iostream>

#include "cli/Commands.hpp"

int main(int argc, char** argv) {
  CLI::App app{"orthosim: soft-tissue simulation for orthognathic surgery planning"};
  app.require_subcommand(1);

  std::string scene, out;
  auto* solve = app.add_subcommand("solve", "Solve an explicit scene (JSON) and write deformed.node and result.json");
  solve->add_option("scene", scene, "Scene file (JSON, see docs/scene-format.md)")->required()->check(CLI::ExistingFile);
  solve->add_option("--out", out, "Output folder")->required();

  std::string demoOut = "orthosim-demo";
  auto* demo = app.add_subcommand("demo", "Write the built-in demo scene and solve it (no data needed)");
  demo->add_option("--out", demoOut, "Output folder (scene/ and result/ inside)");

  orthosim::cli::BenchOptions bench;
  auto* benchCmd = app.add_subcommand("bench", "Time solves of generated blocks with two bonded fragments");
  benchCmd->add_option("--tets", bench.tetCounts, "Approximate tetrahedron counts")->delimiter(',');
  benchCmd->add_option("--repeats", bench.repeats, "Solves per size (median reported)")->check(CLI::Range(1, 100));
  benchCmd->add_option("--json", bench.jsonPath, "Also write the figures to this JSON file");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // Help and version exit 0; any usage error is bad input (exit 1), as for a bad scene.
    return app.exit(e) == 0 ? 0 : 1;
  }
  try {
    if (*solve) return orthosim::cli::runSolve(scene, out);
    if (*demo) return orthosim::cli::runDemo(demoOut);
    if (*benchCmd) return orthosim::cli::runBench(bench);
  } catch (const std::exception& e) {
    std::cerr << "orthosim: " << e.what() << "\n";
    return 1;
  }
  return 1;
}
