#pragma once
// The JSON scene format (docs/scene-format.md). Paths inside a scene are relative to the scene
// file's folder. Every error names the file and the field (and the line of a node-set file).
#include <string>

#include "scene/JsonReader.hpp"
#include "scene/Scene.hpp"
#include "scene/SceneFields.hpp"

namespace orthosim {

// Reads an explicit scene (tetrahedra and node sets) and everything it refers to; throws
// SceneError. Surface-based cases (a "bones" section) are read by scene/CaseFile.hpp.
Scene loadSceneFile(const std::string& path);

}  // namespace orthosim
