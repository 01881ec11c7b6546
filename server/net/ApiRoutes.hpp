#pragma once
// The HTTP API under /api: read-only facts about the server. Everything that changes state
// goes over the WebSocket (/ws, later).
#include <nlohmann/json.hpp>
#include <optional>
#include <string_view>

#include "cases/CaseCatalog.hpp"

namespace orthosim::net {

class ApiRoutes {
 public:
  explicit ApiRoutes(std::vector<server::CaseEntry> cases);

  // The JSON body of GET `path`, or nullopt when no API route has that path.
  std::optional<nlohmann::json> get(std::string_view path) const;

 private:
  nlohmann::json health_, cases_;  // fixed for the server's lifetime: built once
};

}  // namespace orthosim::net
