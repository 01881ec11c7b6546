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

  PlanningService& service_;
  std::string id_;
  SessionState state_;
  SessionChannel channel_;
  SerialWork work_;       // on the preview threads: openings, previews, face fits, exports
  SerialWork frameWork_;  // on the render thread; each frame supersedes the one before
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
