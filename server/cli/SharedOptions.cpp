#include "cli/SharedOptions.hpp"

#include "scene/CaseTissue.hpp"

namespace orthosim::cli {

void addCacheOptions(CLI::App& command, CacheOptions& cache) {
  addCacheFolderOption(command, cache.dir);
  command.add_flag("--no-cache", cache.none, "Build the tissue model even if it is cached, and do not store it");
}

void addCacheFolderOption(CLI::App& command, std::string& dir) {
  dir = defaultCacheDir();
  command.add_option("--cache", dir, "Folder of built tissue models (default: ~/.cache/orthosim)");
}

void addResolutionOption(CLI::App& command, Resolution& resolution, const std::string& description) {
  command
      .add_option_function<std::string>(
          "--resolution",
          [&resolution](const std::string& name) {
            resolution = name == "fine" ? Resolution::Fine : Resolution::Coarse;
          },
          description)
      ->check(CLI::IsMember({"coarse", "fine"}));
}

void addCaseArgument(CLI::App& command, std::string& casePath, const std::string& description) {
  command.add_option("case", casePath, description)->required()->check(CLI::ExistingFile);
}

void addPlanOption(CLI::App& command, std::string& planPath, const std::string& description) {
  command.add_option("--plan", planPath, description)->check(CLI::ExistingFile);
}

void addDataOption(CLI::App& command, std::string& dataDir, const std::string& description) {
  command.add_option("--data", dataDir, description);
}

void addVariantOption(CLI::App& command, int& variant, const std::string& description) {
  command.add_option("--variant", variant, description)->check(CLI::Range(0, 100));
}

void addPatientOption(CLI::App& command, std::vector<std::string>& patientIds) {
  command.add_option("--patient", patientIds, "Only these patients (e.g. --patient M4 --patient M9)");
}

void addRepeatsOption(CLI::App& command, int& repeats, const std::string& description) {
  command.add_option("--repeats", repeats, description)->check(CLI::Range(1, 100));
}

void addJsonOption(CLI::App& command, std::string& jsonPath) {
  command.add_option("--json", jsonPath, "Also write the figures to this JSON file");
}

void addModelMemoryOption(CLI::App& command, int& mebibytes) {
  command
      .add_option("--model-memory", mebibytes,
                  "MiB of built case models kept in memory (an estimate); unused ones beyond go, least recently "
                  "used first (default 2048)")
      ->check(CLI::Range(0, 1 << 20));
}

void addThreadsOption(CLI::App& command, int& threads) {
  command
      .add_option("--threads", threads,
                  "Threads to compute with (default: the cores this process may use, from its affinity and "
                  "cgroup quota); each solve runs on one")
      ->check(CLI::Range(0, 1024));
}

}  // namespace orthosim::cli
