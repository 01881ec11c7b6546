// `resume` (docs/protocol.md, "Fine jobs"): a page that lost its connection (a network drop, or
// the server stopped and started again under the same replica name on Redis) opens its case again
// and takes over the fine jobs its former session left, by that session's id from `welcome`. The
// jobs' outcomes then reach this session as if it had queued them.
#include "session/JobHandler.hpp"
#include "session/OpenCase.hpp"

namespace orthosim::server {
using nlohmann::json;

namespace {

bool isSessionId(const std::string& s) {
  if (s.empty() || s.size() > 64) return false;
  for (const char ch : s)
    if (!((ch >= '0' && ch <= '9') || (ch >= 'a' && ch <= 'f'))) return false;
  return true;
}

}  // namespace

void JobHandler::resume(MessageReader& r, const json& id) {
  const std::shared_ptr<OpenCase> c = state_.requireOpen();
  const std::string former = r.string("session");
  r.rejectUnknown();
  if (!isSessionId(former))
    throw ProtocolError("bad_value",
                        "/session: the former session's id from its welcome (lower-case hex, 1 to 64 characters)",
                        "/session");
  const auto callbacksFor = [this, keep = channel_.keepAlive(), c](const json& context) {
    Poses poses;  // the poses the job was queued with; none when the case changed since
    try {
      if (context.contains("poses"))
        poses = c->readPoses(MessageReader(context["poses"], "/poses"), services_.options.limits);
    } catch (const std::exception&) {
    }
    return fineCallbacks(c, poses);
  };
  // On Redis: round trips to claim the former session's jobs, off the network threads.
  requests_.submit(id, [this, c, former, callbacksFor, id] {
    services_.fineJobs.resume(former, owner_, c->id, callbacksFor, [&](const std::vector<ResumedJob>& jobs) {
      json list = json::array();
      for (const ResumedJob& j : jobs) {
        json item = {{"job", j.job}, {"state", j.state}};
        if (!j.progress.is_null()) {
          item["phase"] = j.progress.value("phase", "");
          item["fraction"] = j.progress.value("fraction", 0.0);
        }
        list.push_back(std::move(item));
      }
      channel_.reply({{"type", "resumed"}, {"session", former}, {"case", c->id}, {"jobs", std::move(list)}}, id);
    });
  });
}

}  // namespace orthosim::server
