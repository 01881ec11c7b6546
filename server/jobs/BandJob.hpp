#pragma once
// A prediction band as one job of the service's job queue, beside the fine jobs:
// the plan solved over the parameter design at coarse or fine resolution, with its progress (which
// solve of how many, the fraction of the whole), its cancellation and its failure as protocol
// messages (docs/protocol.md, "Prediction band"). What the session does with the band is its own.
#include <atomic>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "cases/CaseLibrary.hpp"
#include "eval/PredictionBand.hpp"
#include "jobs/FineJob.hpp"

namespace orthosim::server {

struct BandSolve {
  std::shared_ptr<const CaseModel> model;  // of the resolution the band was solved at
  PredictionBand band;
  double seconds = 0;  // since the job started, the mesh included
};

// Job `job` of case `caseId`: the band of `plan`. Reports job_progress on the way, job_cancelled
// when `cancel` is set, job_failed when the nominal solve does not converge; returns the band
// otherwise (variants that did not converge are in it, named). Other failures throw.
std::optional<BandSolve> runBandJob(long long job, CaseLibrary& cases, const std::string& caseId, Resolution resolution,
                                    const std::map<std::string, FragmentMotion>& plan, const BandOptions& options,
                                    const std::atomic<bool>& cancel, const JobReport& report);

}  // namespace orthosim::server
