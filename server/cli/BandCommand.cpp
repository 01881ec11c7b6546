// `orthosim band CASE.json`: the prediction band of a case's plan: the plan solved
// over the parameter design (engine/eval/PredictionBand), the envelope surfaces written beside the
// nominal skin, the landmark ranges and the parameters' effects in band.json.
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>

#include "cli/CommandLine.hpp"
#include "cli/CommandRun.hpp"
#include "cli/Commands.hpp"
#include "cli/SharedOptions.hpp"
#include "eval/PredictionBandJson.hpp"
#include "io/SurfaceImport.hpp"
#include "scene/PlanFile.hpp"
#include "system/AtomicFile.hpp"

namespace orthosim::cli {
namespace fs = std::filesystem;

namespace {

void writeText(const fs::path& path, const std::string& text) { writeFileAtomically(path, text); }

void writeSurface(const SurfaceMesh& s, const fs::path& path) {
  writeFileAtomicallyWith(path, [&](const fs::path& tmp) { exportSurface(s, tmp.string()); });
}

void printBand(const PredictionBand& band, std::ostream& out) {
  out << std::fixed << std::setprecision(2);
  for (const BandRun& r : band.runs)
    if (!r.converged) out << "run '" << r.run.label << "' did not converge (left out of the band): " << r.error << "\n";
  out << "landmark ranges about the nominal prediction, mm (anterior / superior / right):\n";
  for (const LandmarkRange& l : band.landmarks) {
    out << "  " << std::left << std::setw(18) << l.name << std::right;
    if (!l.measured) {
      out << "not measured: " << l.note << "\n";
      continue;
    }
    for (int k = 0; k < 3; ++k) out << "  " << std::setw(6) << l.low[k] << " .. " << std::setw(5) << l.high[k];
    out << "\n";
  }
  out << "one-at-a-time effect, |high - low| in mm:\n  " << std::setw(18) << "";
  for (const ParameterRange& p : band.design.parameters) out << std::setw(26) << p.name;
  out << "\n";
  for (size_t l = 0; l < band.landmarks.size(); ++l) {
    if (!band.landmarks[l].measured) continue;
    out << "  " << std::left << std::setw(18) << band.landmarks[l].name << std::right;
    for (size_t p = 0; p < band.effect.size(); ++p) {
      if (band.effect[p][l])
        out << std::setw(26) << band.effect[p][l]->norm();
      else
        out << std::setw(26) << "n/a";
    }
    out << "\n";
  }
}

}  // namespace

int runBand(const std::string& casePath, const BandCommandOptions& o) {
  std::unique_ptr<CaseModel> model;
  std::map<std::string, FragmentMotion> plan;
  try {
    const CaseSpec spec = loadCaseFile(casePath);
    plan = o.planPath.empty() ? spec.plan : loadPlanFile(o.planPath, spec);
    CaseTissueOptions t;
    t.cacheDir = o.cacheDir;
    model = std::make_unique<CaseModel>(buildCaseModel(spec, o.resolution, t));
    for (const auto& w : model->warnings) std::cerr << "orthosim: warning: " << w << "\n";
  } catch (const std::exception& e) {
    std::cerr << "orthosim: " << e.what() << "\n";
    return 1;
  }
  BandOptions options;
  options.design.rangeScale = o.rangeScale;
  options.design.corners = !o.noCorners;
  PredictionBand band;
  try {
    BandControl control;
    control.onProgress = [](const BandProgress& p) {
      std::cerr << "\rsolve " << p.solve << "/" << p.solves << " (" << p.run << ")                    " << std::flush;
    };
    band = predictionBand(*model, plan, options, control);
    std::cerr << "\n";
  } catch (const std::invalid_argument& e) {
    std::cerr << "\northosim: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "\northosim: " << e.what() << "\n";
    return 2;
  }
  try {
    fs::create_directories(o.outDir);
    writeSurface(band.envelope.nominal, fs::path(o.outDir) / "nominal.ply");
    writeSurface(band.envelope.lowSurface(), fs::path(o.outDir) / "envelope_low.ply");
    writeSurface(band.envelope.highSurface(), fs::path(o.outDir) / "envelope_high.ply");
    nlohmann::json j = predictionBandJson(band);
    j["case"] = model->spec.name;
    j["resolution"] = resolutionName(o.resolution);
    writeText(fs::path(o.outDir) / "band.json", j.dump(2) + "\n");
  } catch (const std::exception& e) {
    std::cerr << "orthosim: cannot write the band to " << o.outDir << ": " << e.what() << "\n";
    return 1;
  }
  printBand(band, std::cout);
  std::cout << band.runs.size() << " solves (" << band.converged() << " converged) in " << band.seconds
            << " s; band width up to " << band.envelope.width().maxCoeff() << " mm; envelope_low.ply, "
            << "envelope_high.ply, nominal.ply and band.json in " << o.outDir << "\n";
  return band.converged() == static_cast<int>(band.runs.size()) ? 0 : 2;
}

void addBandCommand(CLI::App& parent) {
  struct Args {
    std::string casePath;
    BandCommandOptions options;
    CacheOptions cache;
  };
  auto args = std::make_shared<Args>();
  BandCommandOptions& o = args->options;
  auto* band =
      parent.add_subcommand("band",
                            "Prediction band of a case's plan over the model parameters that change the "
                            "answer: envelope surfaces, landmark ranges and sensitivities (docs/prediction-band.md)");
  addCaseArgument(*band, args->casePath);
  band->add_option("--out", o.outDir, "Output folder")->required();
  addPlanOption(*band, o.planPath,
                "Plan file {fragment: {translation_mm, rotation_deg, center_mm}} instead of the case's plan");
  addResolutionOption(*band, o.resolution, "coarse (preview) or fine (confirm)");
  band->add_option("--range-scale", o.rangeScale, "Scale of every parameter range about the nominal (0, 2]");
  band->add_flag("--no-corners", o.noCorners, "Only the one-at-a-time runs (no factorial corners)");
  addCacheOptions(*band, args->cache);
  runWhenChosen(*band, [args] {
    args->options.cacheDir = args->cache.folder();
    return runBand(args->casePath, args->options);
  });
}

}  // namespace orthosim::cli
