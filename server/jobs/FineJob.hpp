#pragma once
// A confirmed plan solved on the case's fine model, as one job of the service's queue: progress
// as the job goes, and its cancellation or failure, as protocol messages (docs/protocol.md,
// "Fine jobs"). What the session does with a converged result is the session's.
#include <Eigen/Core>
#include <atomic>
#include <functional>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "cases/CaseLibrary.hpp"
#include "scene/CaseModel.hpp"

namespace orthosim::server {

struct FineSolve {
  std::shared_ptr<const CaseModel> model;
  Eigen::Matrix3Xd x;      // the converged nodes
  nlohmann::json figures;  // solveFiguresJson, with "time_s" since the job started
};

// Sends one message about the job to its client; callable from the job's thread.
using JobReport = std::function<void(nlohmann::json message)>;

// Job `job` of case `caseId`: builds (or reuses) the fine model and solves `plan` from rest.
// Reports job_progress on the way, job_cancelled when `cancel` is set, job_failed when the solve
// does not converge; returns the solve only when it converged. Other failures throw.
std::optional<FineSolve> runFineJob(long long job, CaseLibrary& cases, const std::string& caseId,
                                    const std::map<std::string, FragmentMotion>& plan, const std::atomic<bool>& cancel,
                                    const JobReport& report);

}  // namespace orthosim::server
