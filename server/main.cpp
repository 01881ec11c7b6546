// orthosim: soft-tissue prediction for orthognathic surgery planning.
#include <CLI/CLI.hpp>
#include <iostream>

#include "cli/CommandLine.hpp"

int main(int argc, char** argv) {
  CLI::App app{"orthosim: soft-tissue simulation for orthognathic surgery planning"};
  app.require_subcommand(1);
  orthosim::cli::addSolveCommand(app);
  orthosim::cli::addDemoCommand(app);
  orthosim::cli::addBenchCommand(app);
  orthosim::cli::addPhantomCommand(app);
  orthosim::cli::addRenderCommand(app);
  orthosim::cli::addBandCommand(app);
  orthosim::cli::addCompareCommand(app);
  orthosim::cli::addImportCommand(app);
  orthosim::cli::addPlanFromFaceCommand(app);
  orthosim::cli::addServeCommand(app);
  orthosim::cli::addWorkerCommand(app);
  // The chosen command runs inside the parse (cli/CommandRun.hpp).
  try {
    app.parse(argc, argv);
  } catch (const CLI::RuntimeError& e) {
    return e.get_exit_code();  // the command's own exit code; it has said why
  } catch (const CLI::ParseError& e) {
    // Help and version exit 0; any usage error is bad input (exit 1), as for a bad scene.
    return app.exit(e) == 0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::cerr << "orthosim: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
