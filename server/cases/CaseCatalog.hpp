#pragma once
// The cases a client can open: the built-in phantom's variants, the ArtiSynth face shipped with
// the project (cases/artisynth_face), and the case folders of `serve --cases DIR` (each
// DIR/<id>/case.json, docs/scene-format.md).
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace orthosim::server {

struct CaseEntry {
  std::string id;                  // stable identifier a client names the case by, e.g. "phantom-0"
  std::string name;                // short name, e.g. "class-I"
  std::string description;         // for a human
  std::string source;              // where it comes from: "phantom", "artisynth" or "folder"
  int phantomVariant = -1;         // for source "phantom"
  std::filesystem::path caseFile;  // for source "folder": DIR/<id>/case.json
  std::filesystem::path folder;    // for source "artisynth": the shipped face's files
};

inline constexpr const char* kArtisynthFaceId = "artisynth-face";

// The phantom's variants, in variant order (see phantom/Phantom.hpp), then the ArtiSynth face when
// `shipped` holds it (shipped/artisynth_face/face_volume.node).
std::vector<CaseEntry> builtInCases(const std::filesystem::path& shipped = {});

// Every DIR/<id>/case.json whose <id> is a valid identifier, sorted by id. Folders that are not
// cases (no case.json, bad name, unreadable or invalid case file) are left out with a line in
// `skipped` saying why. `known`, when given, tells ids to leave out without reading their case
// file (cases already in a catalog). Throws std::runtime_error when DIR is not a readable folder.
std::vector<CaseEntry> folderCases(const std::filesystem::path& dir, std::vector<std::string>* skipped = nullptr,
                                   const std::function<bool(const std::string&)>& known = {});

// {"cases": [{"id", "name", "description", "source", "variant"?}, ...]} (docs/protocol.md).
nlohmann::json casesJson(const std::vector<CaseEntry>& cases);

}  // namespace orthosim::server
