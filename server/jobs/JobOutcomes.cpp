#include "jobs/JobOutcomes.hpp"

#include <boost/asio/post.hpp>

#include "jobs/JobMessage.hpp"

namespace orthosim::server {
using nlohmann::json;
namespace fs = std::filesystem;

JobOutcomes::JobOutcomes(CaseLibrary& cases, fs::path dataDir, JobRegistry& registry)
    : cases_(cases), dataDir_(std::move(dataDir)), registry_(registry) {}

void JobOutcomes::deliver(OutstandingJob job, json reply) {
  registry_.forget(job);
  const bool done = reply.value("type", "") == "job_done";
  if (done && job.callbacks->doneReply) {  // another kind: its own result handler
    boost::asio::post(loading_, [job = std::move(job), reply = std::move(reply)]() mutable {
      job.callbacks->doneReply(job.id, std::move(reply));
    });
    return;
  }
  if (done) {
    boost::asio::post(loading_, [this, job = std::move(job), reply = std::move(reply)] { loadFine(job, reply); });
    return;
  }
  job.callbacks->report(std::move(reply));
}

// The worker's nodes on this server's fine model of the case (built from the shared cache).
void JobOutcomes::loadFine(const OutstandingJob& job, const json& reply) {
  const fs::path file = dataDir_ / resultFileName(job.name);
  try {
    std::shared_ptr<const CaseModel> fine = cases_.model(job.caseId, Resolution::Fine);
    Eigen::Matrix3Xd x = readResultNodes(file, fine->scene.mesh.numNodes());
    std::error_code ignored;
    fs::remove(file, ignored);  // the session holds it now
    job.callbacks->done(job.id, FineSolve{fine, std::move(x), reply.value("figures", json::object())});
  } catch (const std::exception& e) {
    job.callbacks->report({{"type", "job_failed"},
                           {"job", job.id},
                           {"message", std::string("the fine job's result cannot be used: ") + e.what()}});
  }
}

}  // namespace orthosim::server
