#include "net/ApiRoutes.hpp"

namespace orthosim::net {

ApiRoutes::ApiRoutes(std::vector<server::CaseEntry> cases)
    : health_{{"status", "ok"}, {"version", ORTHOSIM_VERSION}}, cases_(server::casesJson(cases)) {}

std::optional<nlohmann::json> ApiRoutes::get(std::string_view path) const {
  if (path == "/api/health") return health_;
  if (path == "/api/cases") return cases_;
  return std::nullopt;
}

}  // namespace orthosim::net
