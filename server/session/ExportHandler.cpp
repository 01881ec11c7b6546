#include "session/ExportHandler.hpp"

#include "session/OpenCase.hpp"

namespace orthosim::server {
using nlohmann::json;

ExportHandler::ExportHandler(SessionState& state, const SessionChannel& channel, SessionStrand& work,
                             ExportStore& exports, const std::string& owner)
    : state_(state), channel_(channel), work_(work), exports_(exports), owner_(owner) {}

void ExportHandler::exportSkin(MessageReader& r, const json& id) {
  const std::shared_ptr<OpenCase> c = state_.requireOpen();
  const std::string requested = r.string("format");
  const std::string which = r.has("result") ? r.string("result") : "preview";
  r.rejectUnknown();
  const std::string format = skinExportFormat(requested);
  std::shared_ptr<const CaseModel> model;
  std::shared_ptr<const Eigen::Matrix3Xd> x;
  {
    const std::lock_guard<std::mutex> lock(state_.mutex);
    if (which == "preview") {
      model = c->coarse;
      x = c->previewX;
    } else if (which == "fine") {
      const std::shared_ptr<const FineResult>& fine = state_.fine;
      if (fine && fine->caseId == c->id) {
        model = fine->model;
        x = std::shared_ptr<const Eigen::Matrix3Xd>(fine, &fine->x);
      }
    } else {
      throw ProtocolError("bad_value", "/result: '" + which + "' is not one of preview, fine", "/result");
    }
  }
  if (!x)
    throw ProtocolError("no_result", "/result: there is no " + which + " result for case '" + c->id + "' yet",
                        "/result");
  if (model->tissue.skin.numVertices() == 0)
    throw ProtocolError("no_skin", "case '" + c->id + "' has no skin surface to export");
  schedule([this, model, x, format, which, caseId = c->id, id] {
    try {
      offer(skinExportFile(*model, *x, caseId, which, format), {{"format", format}, {"result", which}}, id);
    } catch (const std::exception& e) {
      channel_.sendError("export_failed", std::string("export failed: ") + e.what(), "", id);
    }
  });
}

void ExportHandler::schedule(std::function<void()> body) {
  work_.submit([keep = channel_.keepAlive(), body = std::move(body)](const std::atomic<bool>&) { body(); });
}

void ExportHandler::offer(SkinExport file, json message, const json& id) {
  message["type"] = "exported";
  message["file_name"] = file.fileName;
  message["bytes"] = file.bytes.size();
  message["url"] = "/api/exports/" +
                   exports_.add(owner_, std::move(file.fileName), std::move(file.contentType), std::move(file.bytes));
  channel_.reply(std::move(message), id);
}

}  // namespace orthosim::server
