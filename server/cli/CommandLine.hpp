#pragma once
// The subcommands of `orthosim`: each adds itself to the command line with its own options, and
// runs when chosen (cli/CommandRun.hpp).
namespace CLI {
class App;
}

namespace orthosim::cli {

void addSolveCommand(CLI::App& parent);
void addDemoCommand(CLI::App& parent);
void addBenchCommand(CLI::App& parent);  // `bench` and its benchmarks (cli/BenchCommands.hpp)
void addPhantomCommand(CLI::App& parent);
void addRenderCommand(CLI::App& parent);
void addBandCommand(CLI::App& parent);
void addCompareCommand(CLI::App& parent);
void addImportCommand(CLI::App& parent);
void addPlanFromFaceCommand(CLI::App& parent);
void addServeCommand(CLI::App& parent);
void addWorkerCommand(CLI::App& parent);

}  // namespace orthosim::cli
