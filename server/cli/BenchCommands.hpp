#pragma once
// `orthosim bench MODE`: one subcommand per benchmark, each added by its own file with only its
// own options.
namespace CLI {
class App;
}

namespace orthosim::cli {

void addBlocksBench(CLI::App& bench);
void addPhantomBench(CLI::App& bench);
void addCaseBench(CLI::App& bench);
void addLatencyBench(CLI::App& bench);
void addSessionsBench(CLI::App& bench);
void addRenderBench(CLI::App& bench);
void addCohortBench(CLI::App& bench);
void addBandCohortBench(CLI::App& bench);
void addFaceBench(CLI::App& bench);
void addScanBench(CLI::App& bench);

}  // namespace orthosim::cli
