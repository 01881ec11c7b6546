#include "session/PlanningSession.hpp"

#include <map>

#include "util/ClientText.hpp"
#include "util/RandomId.hpp"

namespace orthosim::server {
using nlohmann::json;

PlanningSession::PlanningSession(PlanningService& service, Send send)
    : service_(service),
      id_(randomHexId()),
      channel_(
          std::move(send), [this] { return std::shared_ptr<const void>(shared_from_this()); }, state_),
      work_(service.previewPool()),
      frameWork_(service.renderPool()),
      openingWork_(service.openingPool()),
      faceFitWork_(service.faceFitPool()),
      exportWork_(service.exportPool()),
      requests_(service.requestPool(), channel_),
      frames_(state_, channel_, frameWork_),
      previews_(state_, channel_, work_, frames_, service.options()),
      exports_(state_, channel_, exportWork_, service.exports(), id_),
      cases_(state_, channel_, work_, openingWork_, requests_, frames_, previews_, service.cases()),
      poses_(state_, channel_, previews_, service.limits()),
      jobs_(
          state_, channel_, work_, requests_, frames_, exports_,
          JobServices{service.fineJobs(), service.localJobs(), service.cases(), service.options(), service.redisJobs()},
          id_),
      plans_(state_, channel_, requests_, previews_, service.plans(), service.limits()),
      faces_(state_, channel_, work_, faceFitWork_, frames_, previews_, service.limits(),
             service.options().faceFitTime) {}

PlanningSession::~PlanningSession() { close(); }

void PlanningSession::start() {
  const PoseLimits& l = service_.limits();
  channel_.reply({{"type", "welcome"},
                  {"session", id_},
                  {"protocol", 1},
                  {"limits", {{"translation_mm", l.translationMm}, {"rotation_deg", l.rotationDeg}}}},
                 nullptr);
}

bool PlanningSession::hasCase() const { return state_.hasCase(); }

void PlanningSession::close() {
  {
    const std::lock_guard<std::mutex> lock(state_.mutex);
    if (state_.closed) return;
    state_.closed = true;
  }
  work_.close();
  frameWork_.close();
  faces_.supersede();
  openingWork_.close();
  faceFitWork_.close();
  exportWork_.close();
  requests_.close();
  service_.fineJobs().releaseOwner(id_);  // on Redis kept a while for a session that resumes them
  service_.localJobs().cancelOwner(id_);
  service_.exports().dropOwner(id_);  // its download links were on its own page
}

void PlanningSession::refuseOversized(std::size_t bytes, std::size_t limit) {
  channel_.sendError("message_too_large",
                     "message of " + std::to_string(bytes) + " bytes or more is over the limit of " +
                         std::to_string(limit) + " bytes; it was ignored",
                     "", nullptr);
}

void PlanningSession::refuseBinary() {
  channel_.sendError("binary_message", "binary messages are not accepted: send JSON text", "", nullptr);
}

void PlanningSession::handle(const std::string& text) {
  json message, id;
  try {
    message = json::parse(text);
  } catch (const json::exception& e) {  // syntax errors, and numbers beyond double (1e999)
    return channel_.sendError("malformed_json", "message is not valid JSON: " + jsonSyntaxMessage(e), "", nullptr);
  }
  try {
    if (message.is_object() && message.contains("id")) {
      id = message["id"];
      const bool ok = (id.is_number_integer()) || (id.is_string() && id.get<std::string>().size() <= 64);
      if (!ok) {
        id = nullptr;
        throw ProtocolError("bad_value", "/id: must be an integer or a string of at most 64 characters", "/id");
      }
    }
    MessageReader r(message, "");
    r.has("id");
    dispatch(r.string("type"), r, id);
  } catch (const ProtocolError& e) {
    channel_.sendError(e.code, e.what(), e.path, id);
  } catch (const std::exception& e) {
    channel_.sendError("internal", std::string("the server could not handle the message: ") + e.what(), "", id);
  }
}

// Each message type to the handler of its concern.
void PlanningSession::dispatch(const std::string& type, MessageReader& r, const json& id) {
  using Handler = void (*)(PlanningSession&, MessageReader&, const json&);
  static const std::map<std::string, Handler> handlers = {
      {"list_cases", [](PlanningSession& s, MessageReader& r, const json& id) { s.cases_.listCases(r, id); }},
      {"open", [](PlanningSession& s, MessageReader& r, const json& id) { s.cases_.open(r, id); }},
      {"describe", [](PlanningSession& s, MessageReader& r, const json& id) { s.cases_.describe(r, id); }},
      {"edit_case", [](PlanningSession& s, MessageReader& r, const json& id) { s.cases_.editCase(r, id); }},
      {"set_poses", [](PlanningSession& s, MessageReader& r, const json& id) { s.poses_.setPoses(r, id); }},
      {"reset", [](PlanningSession& s, MessageReader& r, const json& id) { s.poses_.reset(r, id); }},
      {"preview", [](PlanningSession& s, MessageReader& r, const json& id) { s.poses_.preview(r, id); }},
      {"confirm", [](PlanningSession& s, MessageReader& r, const json& id) { s.jobs_.confirm(r, id); }},
      {"cancel", [](PlanningSession& s, MessageReader& r, const json& id) { s.jobs_.cancel(r, id); }},
      {"resume", [](PlanningSession& s, MessageReader& r, const json& id) { s.jobs_.resume(r, id); }},
      {"band", [](PlanningSession& s, MessageReader& r, const json& id) { s.jobs_.band(r, id); }},
      {"band_view", [](PlanningSession& s, MessageReader& r, const json& id) { s.jobs_.bandView(r, id); }},
      {"export_band", [](PlanningSession& s, MessageReader& r, const json& id) { s.jobs_.exportBand(r, id); }},
      {"list_plans", [](PlanningSession& s, MessageReader& r, const json& id) { s.plans_.listPlans(r, id); }},
      {"save_plan", [](PlanningSession& s, MessageReader& r, const json& id) { s.plans_.savePlan(r, id); }},
      {"load_plan", [](PlanningSession& s, MessageReader& r, const json& id) { s.plans_.loadPlan(r, id); }},
      {"export", [](PlanningSession& s, MessageReader& r, const json& id) { s.exports_.exportSkin(r, id); }},
      {"view", [](PlanningSession& s, MessageReader& r, const json& id) { s.frames_.view(r, id); }},
      {"pick", [](PlanningSession& s, MessageReader& r, const json& id) { s.frames_.pick(r, id); }},
      {"plan_from_face", [](PlanningSession& s, MessageReader& r, const json& id) { s.faces_.planFromFace(r, id); }}};
  auto it = handlers.find(type);
  if (it == handlers.end()) {
    std::string known;
    for (const auto& h : handlers) known += (known.empty() ? "" : ", ") + h.first;
    throw ProtocolError("unknown_type", "/type: unknown message type '" + type + "'; known types: " + known, "/type");
  }
  it->second(*this, r, id);
  supersedeFaceFit(type);  // once accepted: a refused message changes nothing
}

void PlanningSession::supersedeFaceFit(const std::string& type) {
  // plan_from_face supersedes the fit before it itself.
  static const char* const decidingPoses[] = {"open", "edit_case", "set_poses", "reset", "preview", "load_plan"};
  for (const char* t : decidingPoses)
    if (type == t) return faces_.supersede();
}

}  // namespace orthosim::server
