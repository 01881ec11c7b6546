#pragma once
// The phantom's exported case (writePhantomCase into `exportDir`) as a user's import: its surfaces,
// cavity, texture and landmarks, cut by Le Fort I and the bilateral sagittal split.
#include <filesystem>

#include "scene/CaseImport.hpp"

namespace orthosim::test {

inline CaseImportInput phantomImportInput(const std::filesystem::path& exportDir) {
  const auto file = [&](const char* name) { return (exportDir / name).string(); };
  CaseImportInput in;
  in.skin = file("skin.obj");
  in.skull = file("skull.stl");
  in.mandible = file("mandible.stl");
  in.cavities = {file("oral_cavity.stl")};
  in.texture = file("skin.jpg");
  in.landmarks = file("landmarks.json");
  in.cuts = {"le_fort_1", "bsso"};
  return in;
}

}  // namespace orthosim::test
