// `orthosim bench band-cohort`: the sensitivity table of the prediction band: for every patient of the
// synthetic cohort (engine/eval/Cohort) the prediction band of its plan at coarse resolution, and
// per parameter and soft-tissue landmark the median over the patients of the one-at-a-time effect
// |landmark at the high end - at the low end| (bonded minus sliding for the lips): which parameter
// moves which landmark most.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>

#include "cli/BenchCommands.hpp"
#include "cli/BenchContext.hpp"
#include "cli/CommandRun.hpp"
#include "cli/Commands.hpp"
#include "cli/SharedOptions.hpp"
#include "eval/Cohort.hpp"
#include "eval/PredictionBandJson.hpp"
#include "eval/Statistics.hpp"

namespace orthosim::cli {
namespace fs = std::filesystem;
using nlohmann::json;

int runBandCohortBench(const BandCohortBenchOptions& o) {
  std::vector<CohortPatient> patients;
  try {
    patients = selectPatients(o.patients, o.patientIds);
  } catch (const std::exception& e) {
    std::cerr << "orthosim: " << e.what() << "\n";
    return 1;
  }
  const bool temporary = o.dataDir.empty();
  const fs::path dir = temporary ? fs::temp_directory_path() / ("orthosim_band_cohort_" + std::to_string(::getpid()))
                                 : fs::path(o.dataDir);
  std::cout << "band sensitivity on the cohort, coarse, " << utcNow() << ", load " << loadAverage() << "\n";
  // effects[parameter][landmark]: |effect| per patient that has it.
  std::map<std::string, std::map<std::string, std::vector<double>>> effects;
  std::map<std::string, std::map<std::string, std::vector<double>>> anterior, superior;
  std::vector<std::string> parameterOrder, landmarkOrder;
  json rows = json::array();
  std::vector<double> bandSeconds;
  int failed = 0;
  for (const CohortPatient& patient : patients) {
    try {
      const CaseSpec spec = loadCaseFile(writeCohortCase(patient, (dir / patient.id).string()));
      const CaseModel model = buildCaseModel(spec, Resolution::Coarse, {(dir / "cache").string()});
      BandOptions options;
      options.design.corners = o.corners;
      const PredictionBand band = predictionBand(model, spec.plan, options);
      bandSeconds.push_back(band.seconds);
      for (const BandRun& r : band.runs)
        if (!r.converged)
          std::cout << "  " << patient.id << ": run '" << r.run.label << "' did not converge: " << r.error << "\n";
      for (size_t p = 0; p < band.effect.size(); ++p) {
        const std::string& pn = band.design.parameters[p].name;
        if (std::find(parameterOrder.begin(), parameterOrder.end(), pn) == parameterOrder.end())
          parameterOrder.push_back(pn);
        for (size_t l = 0; l < band.landmarks.size(); ++l) {
          const std::string& ln = band.landmarks[l].name;
          if (std::find(landmarkOrder.begin(), landmarkOrder.end(), ln) == landmarkOrder.end())
            landmarkOrder.push_back(ln);
          if (!band.effect[p][l]) continue;
          effects[pn][ln].push_back(band.effect[p][l]->norm());
          anterior[pn][ln].push_back(band.effect[p][l]->x());
          superior[pn][ln].push_back(band.effect[p][l]->y());
        }
      }
      std::cout << "  " << patient.id << " (" << patient.procedure() << "): " << band.runs.size() << " solves, "
                << band.converged() << " converged, " << std::fixed << std::setprecision(1) << band.seconds
                << " s, band width up to " << std::setprecision(2) << band.envelope.width().maxCoeff() << " mm\n";
      json row = predictionBandJson(band);
      row["patient"] = patient.id;
      row["procedure"] = patient.procedure();
      row.erase("runs");
      rows.push_back(std::move(row));
    } catch (const std::exception& e) {
      ++failed;
      std::cout << "  " << patient.id << ": no band: " << e.what() << "\n";
      rows.push_back({{"patient", patient.id}, {"error", e.what()}});
    }
  }
  std::cout << "\nmedian over patients of |effect| (landmark at the high end - at the low end), mm; n = patients\n";
  std::cout << std::setw(18) << "";
  for (const std::string& p : parameterOrder) std::cout << std::setw(26) << p;
  std::cout << "   most\n";
  json table = json::object();
  for (const std::string& l : landmarkOrder) {
    std::cout << std::setw(18) << std::left << l << std::right;
    std::string most;
    double best = -1;
    for (const std::string& p : parameterOrder) {
      const std::vector<double>& v = effects[p][l];
      const double m = median(v);
      char cell[40];
      std::snprintf(cell, sizeof cell, "%.2f (n %zu)", m, v.size());
      std::cout << std::setw(26) << (v.empty() ? std::string("n/a") : std::string(cell));
      table[l][p] = {{"median_mm", v.empty() ? json(nullptr) : json(m)},
                     {"median_anterior_mm", v.empty() ? json(nullptr) : json(median(anterior[p][l]))},
                     {"median_superior_mm", v.empty() ? json(nullptr) : json(median(superior[p][l]))},
                     {"patients", v.size()}};
      if (!v.empty() && m > best) {
        best = m;
        most = p;
      }
    }
    std::cout << "   " << most << "\n";
    table[l]["most"] = most;
  }
  std::cout << "band time per patient (coarse): median " << median(bandSeconds) << " s\n";
  if (!o.jsonPath.empty()) {
    std::ofstream out(o.jsonPath);
    out << json{{"date", utcNow()}, {"load", loadAverage()}, {"table", table}, {"patients", rows}}.dump(2) << "\n";
    if (!out) {
      std::cerr << "orthosim: cannot write " << o.jsonPath << "\n";
      return 1;
    }
  }
  if (temporary) fs::remove_all(dir);
  return failed ? 2 : 0;
}

void addBandCohortBench(CLI::App& bench) {
  auto options = std::make_shared<BandCohortBenchOptions>();
  BandCohortBenchOptions& o = *options;
  auto* bandCohort =
      bench.add_subcommand("band-cohort",
                           "The prediction band's sensitivity table on the synthetic cohort: per "
                           "parameter and soft-tissue landmark, the median one-at-a-time effect (coarse)");
  const int all = static_cast<int>(cohortPatients().size());
  bandCohort->add_option("--patients", o.patients, "The first N patients (default: all)")->check(CLI::Range(1, all));
  addPatientOption(*bandCohort, o.patientIds);
  bandCohort->add_flag("--corners", o.corners, "Also solve the factorial corners (the table needs only the others)");
  addDataOption(*bandCohort, o.dataDir, "Folder for the cohort's cases and tissue cache (kept)");
  addJsonOption(*bandCohort, o.jsonPath);
  runWhenChosen(*bandCohort, [options] { return runBandCohortBench(*options); });
}

}  // namespace orthosim::cli
