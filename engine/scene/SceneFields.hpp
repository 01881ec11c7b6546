#pragma once
// Fields that explicit scenes and surface-based cases share (docs/scene-format.md): material,
// plan motions, solver settings, node sets, and how paths and files are read.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "scene/JsonReader.hpp"
#include "scene/Scene.hpp"

namespace orthosim {

// The file's JSON; a syntax error is a SceneError "<path>: malformed JSON: ...".
nlohmann::json parseJsonFile(const std::string& path);
// `p` relative to the folder `base` unless it is absolute.
std::string resolvePath(const std::string& base, const std::string& p);

// tissue.material: sets youngsModulus (MPa) and poissonRatio.
void readMaterial(JsonReader r, double& youngsModulus, double& poissonRatio);
// One plan entry: translation_mm, rotation_deg, center_mm.
FragmentMotion readFragmentMotion(JsonReader r);
void readSolverSettings(JsonReader r, SolverSettings& s);
// components: letters from "xyz"; all three when absent.
std::array<bool, 3> readComponents(JsonReader& r);

// One 0-based node index per line ('#' comments and blank lines allowed), each checked against
// numNodes. `field` names the scene field the file came from, for errors.
std::vector<int> readNodeSet(const std::string& path, int numNodes, const std::string& field);

}  // namespace orthosim
