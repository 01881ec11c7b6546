#pragma once
// Options that several subcommands take, each declared here once so that its name, check and
// help read the same wherever it appears.
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "scene/CaseFile.hpp"

namespace orthosim::cli {

// --cache DIR and --no-cache: where built tissue models are kept, or nowhere.
struct CacheOptions {
  std::string dir;  // the folder; addCacheOptions starts it at defaultCacheDir()
  bool none = false;
  // The folder the command passes on; empty: build the model every time and store nothing.
  std::string folder() const { return none ? std::string() : dir; }
};
void addCacheOptions(CLI::App& command, CacheOptions& cache);
// --cache DIR alone (for a command without --no-cache); `dir` starts as defaultCacheDir().
void addCacheFolderOption(CLI::App& command, std::string& dir);

// --resolution coarse|fine.
void addResolutionOption(CLI::App& command, Resolution& resolution, const std::string& description);

// The positional "case": an existing surface-based case file.
void addCaseArgument(CLI::App& command, std::string& casePath,
                     const std::string& description = "Surface-based case file (JSON)");

// --plan FILE: an existing plan file solved instead of the case's plan.
void addPlanOption(CLI::App& command, std::string& planPath, const std::string& description);

// --data DIR: the folder a command keeps its cases, caches or results in.
void addDataOption(CLI::App& command, std::string& dataDir, const std::string& description);

// --variant N: which phantom morphology.
void addVariantOption(CLI::App& command, int& variant, const std::string& description = "Phantom variant");

// --patient ID (repeatable): cohort patients by name.
void addPatientOption(CLI::App& command, std::vector<std::string>& patientIds);

// --repeats N (1 to 100): runs of a benchmark.
void addRepeatsOption(CLI::App& command, int& repeats, const std::string& description);

// --json FILE: a machine-readable copy of what the command prints.
void addJsonOption(CLI::App& command, std::string& jsonPath);

// --model-memory MIB: built case models kept in memory (cases/CaseLibrary), an estimate.
void addModelMemoryOption(CLI::App& command, int& mebibytes);

// --threads N: the process's thread budget (system/ThreadBudget; 0, the default: the usable cores).
void addThreadsOption(CLI::App& command, int& threads);

}  // namespace orthosim::cli
