#pragma once
// How a subcommand runs: its CLI11 callback calls `run` once the command line is parsed. A
// nonzero exit code leaves the parse as CLI::RuntimeError, which carries it to main unprinted;
// an exception of `run` leaves it as it is, for main to print.
#include <CLI/CLI.hpp>
#include <functional>

namespace orthosim::cli {

inline void runWhenChosen(CLI::App& command, std::function<int()> run) {
  command.callback([run = std::move(run)] {
    if (const int code = run()) throw CLI::RuntimeError(code);
  });
}

}  // namespace orthosim::cli
