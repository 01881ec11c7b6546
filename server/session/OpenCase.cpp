#include "session/OpenCase.hpp"

#include "session/ProtocolError.hpp"

namespace orthosim::server {

std::map<std::string, AnatomicalPose> OpenCase::readPoses(MessageReader r, const PoseLimits& limits) const {
  std::map<std::string, AnatomicalPose> poses;
  for (const auto& item : r.raw().items()) {
    const std::string& name = item.key();
    if (!fragment(name)) {
      std::string known;
      for (const PlanningFragment& f : fragments) known += (known.empty() ? "" : ", ") + f.name;
      throw ProtocolError(
          "unknown_fragment",
          r.pointer(name) + ": no movable fragment '" + name + "' in case '" + id + "'; movable fragments: " + known,
          r.pointer(name));
    }
    poses[name] = readPose(r.object(name), limits);
  }
  return poses;
}

}  // namespace orthosim::server
