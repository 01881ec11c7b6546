// `orthosim bench scan [--size I J K] [--repeats N] [--json F]`: how long a CT series takes to
// become a plannable case - read, segmented, surfaces, landmarks, oral cavity, case written (the
// import), then the coarse model built and its plan solved - on the phantom scanned as a head CT
// (phantom/PhantomCt: 512 x 512 x 300 voxels by default). Medians of the runs; no tissue cache, so
// every run meshes anew, as a new patient does.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <thread>

#include "cli/BenchCommands.hpp"
#include "cli/CommandRun.hpp"
#include "cli/Commands.hpp"
#include "cli/SharedOptions.hpp"
#include "eval/Statistics.hpp"
#include "phantom/PhantomCase.hpp"
#include "phantom/PhantomCt.hpp"
#include "scene/CaseImport.hpp"
#include "scene/CaseModel.hpp"
#include "solver/PlanSolver.hpp"
#include "volume/DicomSeries.hpp"

namespace orthosim::cli {
namespace {
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

struct ScanRun {
  double read = 0, segment = 0, import = 0, model = 0, solve = 0;
};

// One run: the reading and segmentation timed on their own, then the whole import and the model.
ScanRun runOnce(const fs::path& series, const fs::path& caseDir) {
  ScanRun r;
  auto t0 = Clock::now();
  const CtVolume volume = readDicomSeries(series.string());
  r.read = since(t0);
  t0 = Clock::now();
  segmentCt(volume);
  r.segment = since(t0);
  CaseImportInput in;
  in.dicom = series.string();
  in.cuts = {"le_fort_1", "bsso"};
  t0 = Clock::now();
  const CaseImportReport report = importCase(in, caseDir.string());
  r.import = since(t0);
  CaseSpec spec = loadCaseFile(report.caseFile);
  FragmentMotion advance;
  advance.translation = Eigen::Vector3d(0, -5, 0);  // LPS: 5 mm anterior
  spec.plan = {{"maxilla", advance}};
  t0 = Clock::now();
  const CaseModel model = buildCaseModel(spec, Resolution::Coarse);
  r.model = since(t0);
  Model m(model.scene);
  t0 = Clock::now();
  const SolveResult result = solveScene(m);
  r.solve = since(t0);
  if (!result.converged) throw std::runtime_error("the Le Fort I preview did not converge: " + result.error);
  return r;
}

}  // namespace

int runScanBench(const ScanBenchOptions& opt) {
  const fs::path work = fs::temp_directory_path() / ("orthosim_scan_bench_" + std::to_string(::getpid()));
  fs::remove_all(work);
  PhantomScanOptions scan;
  scan.size = Eigen::Vector3i(opt.size[0], opt.size[1], opt.size[2]);
  auto t0 = Clock::now();
  writePhantomCase(0, (work / "phantom").string());
  const PhantomCt ct = phantomCt((work / "phantom").string(), scan);
  writeDicomSeries(ct.ct, (work / "series").string());
  const Eigen::Vector3d h = ct.ct.spacing();
  std::printf(
      "orthosim bench scan: the phantom as a %d x %d x %d CT of %.2f x %.2f x %.2f mm (made in %.1f s); "
      "medians of %d runs; %u hardware threads\n",
      opt.size[0], opt.size[1], opt.size[2], h.x(), h.y(), h.z(), since(t0), opt.repeats,
      std::thread::hardware_concurrency());
  std::vector<double> read, segment, import, model, solve, total;
  for (int k = 0; k < opt.repeats; ++k) {
    const ScanRun r = runOnce(work / "series", work / ("case_" + std::to_string(k)));
    read.push_back(r.read), segment.push_back(r.segment), import.push_back(r.import);
    model.push_back(r.model), solve.push_back(r.solve), total.push_back(r.import + r.model + r.solve);
    std::printf(
        "run %d: read %.1f s, segment %.1f s; import %.1f s (read, segment, surfaces, landmarks, cavity, "
        "checks); coarse model %.1f s; Le Fort I preview %.1f s; scan to preview %.1f s\n",
        k + 1, r.read, r.segment, r.import, r.model, r.solve, total.back());
  }
  std::printf(
      "median: import %.1f s (of it read %.1f s, segment %.1f s), coarse model %.1f s, preview %.1f s; "
      "scan to preview %.1f s\n",
      median(import), median(read), median(segment), median(model), median(solve), median(total));
  if (!opt.jsonPath.empty()) {
    const nlohmann::json out = {{"size", opt.size},
                                {"spacing_mm", {h.x(), h.y(), h.z()}},
                                {"repeats", opt.repeats},
                                {"read_s", median(read)},
                                {"segment_s", median(segment)},
                                {"import_s", median(import)},
                                {"coarse_model_s", median(model)},
                                {"preview_s", median(solve)},
                                {"scan_to_preview_s", median(total)}};
    std::ofstream(opt.jsonPath) << out.dump(2) << "\n";
  }
  fs::remove_all(work);
  return 0;
}

void addScanBench(CLI::App& bench) {
  auto options = std::make_shared<ScanBenchOptions>();
  auto* scan =
      bench.add_subcommand("scan", "Time a CT series (the phantom scanned) to a plannable case and its preview");
  scan->add_option("--size", options->size, "The CT's voxels i j k (default 512 512 300)")
      ->expected(3)
      ->check(CLI::Range(32, 1024));
  addRepeatsOption(*scan, options->repeats, "Runs (medians reported)");
  addJsonOption(*scan, options->jsonPath);
  runWhenChosen(*scan, [options] { return runScanBench(*options); });
}

}  // namespace orthosim::cli
