#pragma once
// One client's planning session (one WebSocket connection): the case it has open, the fragment
// poses, the newest coarse preview, its fine jobs. handle() runs on the connection's network
// strand and only parses, validates and schedules: solves run on the service's threads and
// report back through `send`, which may be called from any thread. docs/protocol.md lists every
// message.
#include <Eigen/Core>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>

#include "eval/PredictionBand.hpp"
#include "jobs/BandResultFile.hpp"
#include "jobs/FineJob.hpp"
#include "planning/FaceRequestJson.hpp"
#include "session/AnatomicalPose.hpp"
#include "session/MessageReader.hpp"
#include "session/PlanningService.hpp"
#include "session/SerialWork.hpp"
#include "session/SessionView.hpp"
#include "session/SkinExport.hpp"

namespace orthosim::server {

class PlanningSession : public std::enable_shared_from_this<PlanningSession> {
 public:
  // Sends a text message, or a binary one (a JPEG frame); callable from any thread.
  using Send = std::function<void(const std::string& bytes, bool binary)>;

  PlanningSession(PlanningService& service, Send send);
  ~PlanningSession();

  const std::string& id() const { return id_; }
  void start();                          // sends "welcome"
  void handle(const std::string& text);  // one client message
  void refuseOversized(std::size_t bytes, std::size_t limit);
  void refuseBinary();
  // The connection is gone: cancel previews and band jobs; fine jobs are cancelled too, or on
  // Redis kept a while for a session that resumes them. Idempotent.
  void close();
  // A case is open or being opened (a session that never gets this far holds a slot for nothing).
  bool hasCase() const;

 private:
  struct OpenCase;
  struct FineResult;

  void dispatch(const std::string& type, MessageReader& r, const nlohmann::json& id);
  void listCases(MessageReader& r, const nlohmann::json& id);
  void open(MessageReader& r, const nlohmann::json& id);
  // Replies "opening", then builds (or takes the built) models on the session's work queue with
  // "open_progress", then "opened".
  void startOpening(const std::string& caseId, const nlohmann::json& id);
  // An imported patient's landmarks and osteotomies changed (session/CaseEditMessage.cpp).
  void editCase(MessageReader& r, const nlohmann::json& id);
  // The prediction band (session/BandMessage.cpp): a band job, its extremes shown, its surfaces exported.
  struct BandResult;
  void band(MessageReader& r, const nlohmann::json& id);
  void bandView(MessageReader& r, const nlohmann::json& id);
  void exportBand(MessageReader& r, const nlohmann::json& id);
  void runBand(long long job, const std::string& caseId, Resolution resolution,
               const std::map<std::string, FragmentMotion>& plan, const nlohmann::json& poses,
               const BandOptions& options, const std::atomic<bool>& cancel);
  // What a job of the open case's current poses needs; throws case_not_open as requireOpen does.
  struct PlanSnapshot {
    std::string caseId;
    std::shared_ptr<const CaseModel> coarse;
    std::map<std::string, FragmentMotion> plan;
    nlohmann::json poses;
  };
  PlanSnapshot planSnapshot() const;
  // A band job on the workers (`serve --redis`), and a finished band from either place
  // (session/BandMessage.cpp): band_done and the view's band.
  void submitRedisBand(const PlanSnapshot& s, Resolution resolution, const BandOptions& options, size_t solves,
                       const nlohmann::json& id);
  void publishBand(long long job, const std::string& caseId, Resolution resolution, const nlohmann::json& poses,
                   BandOutcome outcome);
  std::string openCaseId() const;  // throws case_not_open as requireOpen does
  void describe(MessageReader& r, const nlohmann::json& id);
  void setPoses(MessageReader& r, const nlohmann::json& id);
  void reset(MessageReader& r, const nlohmann::json& id);
  void preview(MessageReader& r, const nlohmann::json& id);
  void confirm(MessageReader& r, const nlohmann::json& id);
  void cancel(MessageReader& r, const nlohmann::json& id);
  // Takes over the fine jobs a former session of this client left (session/ResumeMessage.cpp).
  void resume(MessageReader& r, const nlohmann::json& id);
  // Publishes a fine job's outcome of `poses` on case `c` to this session.
  FineJobCallbacks fineCallbacks(const std::shared_ptr<OpenCase>& c,
                                 const std::map<std::string, AnatomicalPose>& poses);
  void listPlans(MessageReader& r, const nlohmann::json& id);
  void savePlan(MessageReader& r, const nlohmann::json& id);
  void loadPlan(MessageReader& r, const nlohmann::json& id);
  void exportSkin(MessageReader& r, const nlohmann::json& id);
  void offerExport(SkinExport file, nlohmann::json message, const nlohmann::json& id);
  void view(MessageReader& r, const nlohmann::json& id);
  void pick(MessageReader& r, const nlohmann::json& id);
  // Poses from soft-tissue landmark targets (session/FaceTargetMessage.cpp).
  void planFromFace(MessageReader& r, const nlohmann::json& id);
  void checkFaceRequest(const FaceRequest& face, const OpenCase& c) const;
  void runFaceFit(const std::shared_ptr<OpenCase>& c, const FaceRequest& face,
                  const std::map<std::string, AnatomicalPose>& start, const nlohmann::json& id,
                  const std::atomic<bool>& cancel);
  void requestFrame();
  void showLinear(const nlohmann::json& id);
  void scheduleDragResponse(const std::shared_ptr<OpenCase>& c, long long seq, const SimState& state);
  void postCoarseFineDifference(const CaseModel& coarse, const Eigen::Matrix3Xd& coarseX, const CaseModel& fine,
                                const Eigen::Matrix3Xd& fineX);

  std::shared_ptr<OpenCase> requireOpen() const;  // throws case_not_open
  std::map<std::string, AnatomicalPose> readPoses(MessageReader r, const OpenCase& c) const;
  void schedulePreview(const nlohmann::json& id);
  void runPreview(const std::shared_ptr<OpenCase>& c, long long seq, std::map<std::string, AnatomicalPose> poses,
                  const nlohmann::json& id, const std::atomic<bool>& cancel);
  void publishFine(long long job, const std::shared_ptr<OpenCase>& c, std::map<std::string, AnatomicalPose> poses,
                   FineSolve solved);
  nlohmann::json posesJson() const;  // with mutex_ held
  nlohmann::json caseJson(const OpenCase& c) const;

  void reply(nlohmann::json message, const nlohmann::json& id);
  void sendError(const std::string& code, const std::string& message, const std::string& path,
                 const nlohmann::json& id);

  PlanningService& service_;
  Send send_;
  std::string id_;
  SerialWork work_;
  SerialWork frames_;  // on the render thread; each frame supersedes the one before
  mutable std::mutex mutex_;
  bool closed_ = false;
  std::shared_ptr<OpenCase> open_;
  std::string opening_;  // id of a case being opened
  std::map<std::string, AnatomicalPose> poses_;
  long long previewSeq_ = 0;
  std::shared_ptr<const FineResult> fine_;  // the newest finished fine job
  std::shared_ptr<const BandResult> band_;  // the newest finished band job
  std::shared_ptr<SessionView> view_;       // of the open case
  bool renderFailed_ = false;               // said once; no frames after
};

}  // namespace orthosim::server
