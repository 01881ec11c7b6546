#include "cases/CaseCatalog.hpp"

#include <algorithm>

#include "cases/Identifier.hpp"
#include "phantom/Phantom.hpp"
#include "scene/CaseFile.hpp"

namespace orthosim::server {
namespace fs = std::filesystem;

std::vector<CaseEntry> builtInCases(const fs::path& shipped) {
  std::vector<CaseEntry> cases;
  for (const PhantomVariant& v : phantomVariants())
    cases.push_back({"phantom-" + std::to_string(v.index), v.name, v.description, "phantom", v.index, {}, {}});
  std::error_code ec;
  if (!shipped.empty() && fs::is_regular_file(shipped / "artisynth_face" / "face_volume.node", ec))
    cases.push_back({kArtisynthFaceId,
                     "ArtiSynth face",
                     "a real adult face (the ArtiSynth Badin model: 37098 tetrahedra; BSD-style licence, "
                     "cases/artisynth_face/README.md): Le Fort I and BSSO, lips-teeth contact",
                     "artisynth",
                     -1,
                     {},
                     shipped / "artisynth_face"});
  return cases;
}

std::vector<CaseEntry> folderCases(const fs::path& dir, std::vector<std::string>* skipped,
                                   const std::function<bool(const std::string&)>& known) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw std::runtime_error("cases folder " + dir.string() + " is not a folder");
  std::vector<CaseEntry> cases;
  for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
    const std::string id = e.path().filename().string();
    const fs::path file = e.path() / "case.json";
    if (!e.is_directory() || !fs::is_regular_file(file) || (known && known(id))) continue;
    auto skip = [&](const std::string& why) {
      if (skipped) skipped->push_back(e.path().string() + ": " + why);
    };
    if (!isIdentifier(id)) {
      skip("folder name is not an identifier (letters, digits, '_' and '-')");
      continue;
    }
    try {
      const CaseSpec spec = loadCaseFile(file.string());  // a broken case is reported now, not at open
      cases.push_back(
          {id, spec.name.empty() ? id : spec.name, "case folder " + id, "folder", -1, fs::absolute(file), {}});
    } catch (const std::exception& ex) {
      skip(ex.what());
    }
  }
  if (ec) throw std::runtime_error("cannot read cases folder " + dir.string() + ": " + ec.message());
  std::sort(cases.begin(), cases.end(), [](const CaseEntry& a, const CaseEntry& b) { return a.id < b.id; });
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
