#include "cli/BenchCommands.hpp"

#include <CLI/CLI.hpp>

#include "cli/CommandLine.hpp"

namespace orthosim::cli {

void addBenchCommand(CLI::App& parent) {
  auto* bench = parent.add_subcommand("bench",
                                      "Time and measure: generated blocks, case models, the planning server, "
                                      "rendering, the synthetic cohort");
  bench->require_subcommand(1);
  addBlocksBench(*bench);
  addPhantomBench(*bench);
  addCaseBench(*bench);
  addLatencyBench(*bench);
  addSessionsBench(*bench);
  addRenderBench(*bench);
  addCohortBench(*bench);
  addBandCohortBench(*bench);
  addFaceBench(*bench);
  addScanBench(*bench);
}

}  // namespace orthosim::cli
