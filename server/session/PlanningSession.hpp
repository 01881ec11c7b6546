#pragma once
// One client's planning session (one WebSocket connection). handle() runs on the connection's
// network strand and hands each message to the handler of its concern (cases, poses, jobs, plans,
// frames, exports, face fits), which parses, validates and schedules: solves run on the service's
// threads and report back through `send`, which may be called from any thread. The session owns
// the state the handlers share and the serial work they schedule on. docs/protocol.md lists every
// message.
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "schedule/SerialWork.hpp"
#include "schedule/SessionStrand.hpp"
#include "session/CaseHandler.hpp"
#include "session/ExportHandler.hpp"
#include "session/FaceHandler.hpp"
#include "session/FrameHandler.hpp"
#include "session/JobHandler.hpp"
#include "session/MessageReader.hpp"
#include "session/PlanHandler.hpp"
#include "session/PlanningService.hpp"
#include "session/PoseHandler.hpp"
#include "session/PreviewScheduler.hpp"
#include "session/RequestWork.hpp"
#include "session/SessionChannel.hpp"
#include "session/SessionState.hpp"

namespace orthosim::server {

class PlanningSession : public std::enable_shared_from_this<PlanningSession> {
 public:
  // Sends a text message, or a binary one (a JPEG frame); callable from any thread.
  using Send = SessionChannel::Send;

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
  void dispatch(const std::string& type, MessageReader& r, const nlohmann::json& id);
  // Messages that decide the poses (or the case) stop a running face fit first.
  void supersedeFaceFit(const std::string& type);

  PlanningService& service_;
  std::string id_;
  SessionState state_;
  SessionChannel channel_;
  SerialWork work_;       // on the preview threads: previews, and what uses the session's model
  SerialWork frameWork_;  // on the render thread; each frame supersedes the one before
  // Below the previews, each on its pool, in the session's order: building the models of a case,
  // face fits, exports, and the requests that wait on the disk or Redis.
  SessionStrand openingWork_;
  SessionStrand faceFitWork_;
  SessionStrand exportWork_;
  RequestWork requests_;
  FrameHandler frames_;
  PreviewScheduler previews_;
  ExportHandler exports_;
  CaseHandler cases_;
  PoseHandler poses_;
  JobHandler jobs_;
  PlanHandler plans_;
  FaceHandler faces_;
};

}  // namespace orthosim::server
