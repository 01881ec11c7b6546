#pragma once
// A session's exports (docs/protocol.md, "Export"): `export` writes the skin of the newest preview
// or fine result on the export pool, below the previews (it reads shared results, never the
// session's model); every exported file, the band's too, is offered as a download link of this
// session's own (session/ExportStore).
#include <nlohmann/json.hpp>
#include <string>

#include "schedule/SessionStrand.hpp"
#include "session/ExportStore.hpp"
#include "session/MessageReader.hpp"
#include "session/SessionChannel.hpp"
#include "session/SessionState.hpp"
#include "session/SkinExport.hpp"

namespace orthosim::server {

class ExportHandler {
 public:
  // `owner`: the session's id, whose links these are.
  // `work`: the session's work on the export pool.
  ExportHandler(SessionState& state, const SessionChannel& channel, SessionStrand& work, ExportStore& exports,
                const std::string& owner);

  void exportSkin(MessageReader& r, const nlohmann::json& id);
  // An export's work, after the session's earlier exports; `body` replies itself.
  void schedule(std::function<void()> body);
  // The file to the exports, and `exported` with its link; `message` says what it is.
  void offer(SkinExport file, nlohmann::json message, const nlohmann::json& id);

 private:
  SessionState& state_;
  const SessionChannel& channel_;
  SessionStrand& work_;
  ExportStore& exports_;
  const std::string& owner_;
};

}  // namespace orthosim::server
