#pragma once
// The cases a client can open. For now the built-in phantom's variants; cases read from a
// folder (`serve --cases DIR`) join this list later.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace orthosim::server {

struct CaseEntry {
  std::string id;           // stable identifier a client names the case by, e.g. "phantom-0"
  std::string name;         // short name, e.g. "class-I"
  std::string description;  // for a human
  std::string source;       // where it comes from: "phantom"
  int phantomVariant = -1;  // for source "phantom"
};

// The phantom's variants, in variant order (see phantom/Phantom.hpp).
std::vector<CaseEntry> builtInCases();

// {"cases": [{"id", "name", "description", "source", "variant"?}, ...]} (docs/protocol.md).
nlohmann::json casesJson(const std::vector<CaseEntry>& cases);

}  // namespace orthosim::server
