#pragma once
// `orthosim bench MODE`: one subcommand per benchmark (blocks, phantom, case, latency, render,
// cohort, scan), each with only its own options.
#include <CLI/CLI.hpp>

#include "cli/Commands.hpp"

namespace orthosim::cli {

class BenchCommands {
 public:
  // Adds "bench" and its subcommands to `app`; the options are bound to this object, which must
  // outlive the parse.
  explicit BenchCommands(CLI::App& app);
  BenchCommands(const BenchCommands&) = delete;
  BenchCommands& operator=(const BenchCommands&) = delete;

  bool chosen() const { return bench_->parsed(); }
  // Runs the chosen benchmark; its exit code.
  int run() const;

 private:
  void addBlocks();
  void addPhantom();
  void addCase();
  void addLatency();
  void addSessions();
  void addRender();
  void addCohort();
  void addBandCohort();
  void addFace();
  void addScan();

  CLI::App* bench_ = nullptr;
  CLI::App *blocks_ = nullptr, *phantom_ = nullptr, *case_ = nullptr, *latency_ = nullptr, *render_ = nullptr,
           *cohort_ = nullptr, *sessions_ = nullptr, *bandCohort_ = nullptr, *face_ = nullptr, *scan_ = nullptr;
  BenchOptions blocksOptions_;
  CaseBenchOptions phantomOptions_, caseOptions_;
  LatencyBenchOptions latencyOptions_;
  SessionsBenchOptions sessionsOptions_;
  RenderBenchOptions renderOptions_;
  CohortBenchOptions cohortOptions_;
  BandCohortBenchOptions bandCohortOptions_;
  FaceBenchOptions faceOptions_;
  ScanBenchOptions scanOptions_;
};

}  // namespace orthosim::cli
