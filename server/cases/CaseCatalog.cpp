#include "cases/CaseCatalog.hpp"

#include "phantom/Phantom.hpp"

namespace orthosim::server {

std::vector<CaseEntry> builtInCases() {
  std::vector<CaseEntry> cases;
  for (const PhantomVariant& v : phantomVariants())
    cases.push_back({"phantom-" + std::to_string(v.index), v.name, v.description, "phantom", v.index});
  return cases;
}

nlohmann::json casesJson(const std::vector<CaseEntry>& cases) {
  nlohmann::json list = nlohmann::json::array();
  for (const CaseEntry& c : cases) {
    nlohmann::json entry = {{"id", c.id}, {"name", c.name}, {"description", c.description}, {"source", c.source}};
    if (c.source == "phantom") entry["variant"] = c.phantomVariant;
    list.push_back(std::move(entry));
  }
  return {{"cases", std::move(list)}};
}

}  // namespace orthosim::server
