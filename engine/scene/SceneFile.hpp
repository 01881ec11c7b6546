#pragma once
// The JSON scene format (docs/scene-format.md). Paths inside a scene are relative to the scene
// file's folder. Every error names the file and the field (and the line of a node-set file).
#include <string>

#include "scene/Scene.hpp"

namespace orthosim {

// Reads a scene and everything it refers to; throws SceneError.
Scene loadSceneFile(const std::string& path);

struct SceneError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// One 0-based node index per line ('#' comments and blank lines allowed), each checked against
// numNodes. `field` names the scene field the file came from, for errors.
std::vector<int> readNodeSet(const std::string& path, int numNodes, const std::string& field);

}  // namespace orthosim
