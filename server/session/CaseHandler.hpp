#pragma once
// The case of a session (docs/protocol.md, "Cases"): `list_cases`, `open` (its models built or
// taken built on the opening pool, below the previews, with progress; then opened on the session's
// serial work, after its earlier work), `describe`, and `edit_case`, which rewrites an imported
// patient's case file and opens it again (session/CaseEditMessage.cpp).
#include <nlohmann/json.hpp>
#include <string>

#include "cases/CaseLibrary.hpp"
#include "schedule/SerialWork.hpp"
#include "schedule/SessionStrand.hpp"
#include "session/FrameHandler.hpp"
#include "session/MessageReader.hpp"
#include "session/PreviewScheduler.hpp"
#include "session/RequestWork.hpp"
#include "session/SessionChannel.hpp"
#include "session/SessionState.hpp"

namespace orthosim::server {

class CaseHandler {
 public:
  // `openings`: the session's work on the opening pool; `requests`: its disk requests.
  CaseHandler(SessionState& state, const SessionChannel& channel, SerialWork& work, SessionStrand& openings,
              RequestWork& requests, FrameHandler& frames, PreviewScheduler& previews, CaseLibrary& cases);

  void listCases(MessageReader& r, const nlohmann::json& id);
  void open(MessageReader& r, const nlohmann::json& id);
  void describe(MessageReader& r, const nlohmann::json& id);
  void editCase(MessageReader& r, const nlohmann::json& id);

 private:
  // Replies "opening", then builds (or takes the built) models on the opening pool with
  // "open_progress", then "opened" on the session's serial work.
  void startOpening(const std::string& caseId, const nlohmann::json& id);
  // The case's models and fragments; throws what building them throws.
  std::shared_ptr<OpenCase> build(const std::string& caseId, const nlohmann::json& id, const std::atomic<bool>& cancel);
  void opened(const std::shared_ptr<OpenCase>& c, double seconds, const nlohmann::json& id);
  nlohmann::json caseJson(const OpenCase& c) const;  // with the state's mutex held

  SessionState& state_;
  const SessionChannel& channel_;
  SerialWork& work_;
  SessionStrand& openings_;
  RequestWork& requests_;
  FrameHandler& frames_;
  PreviewScheduler& previews_;
  CaseLibrary& cases_;
};

}  // namespace orthosim::server
