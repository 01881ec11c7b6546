#include "jobs/BandJob.hpp"

#include <chrono>

namespace orthosim::server {
using nlohmann::json;

std::optional<BandSolve> runBandJob(long long job, CaseLibrary& cases, const std::string& caseId, Resolution resolution,
                                    const std::map<std::string, FragmentMotion>& plan, const BandOptions& options,
                                    const std::atomic<bool>& cancel, const JobReport& report) {
  const auto t0 = std::chrono::steady_clock::now();
  // Fractions: the mesh (cached after the first time) to 0.1, the solves over the rest.
  report({{"type", "job_progress"}, {"job", job}, {"kind", "band"}, {"phase", "mesh"}, {"fraction", 0.0}});
  std::shared_ptr<const CaseModel> model = cases.model(caseId, resolution);
  if (cancel) {
    report({{"type", "job_cancelled"}, {"job", job}, {"kind", "band"}, {"phase", "mesh"}});
    return std::nullopt;
  }
  BandControl control;
  control.cancel = &cancel;
  control.onProgress = [&](const BandProgress& p) {
    report({{"type", "job_progress"},
            {"job", job},
            {"kind", "band"},
            {"phase", "solve"},
            {"solve", p.solve},
            {"solves", p.solves},
            {"run", p.run},
            {"fraction", 0.1 + 0.9 * p.fraction}});
  };
  PredictionBand band;
  try {
    band = predictionBand(*model, plan, options, control);
  } catch (const std::runtime_error& e) {  // the nominal solve failed: there is no band
    report({{"type", "job_failed"}, {"job", job}, {"kind", "band"}, {"message", e.what()}});
    return std::nullopt;
  }
  if (band.cancelled) {
    report({{"type", "job_cancelled"},
            {"job", job},
            {"kind", "band"},
            {"phase", "solve"},
            {"solved", band.runs.size()},
            {"solves", band.design.runs.size()}});
    return std::nullopt;
  }
  return BandSolve{std::move(model), std::move(band),
                   std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()};
}

}  // namespace orthosim::server
