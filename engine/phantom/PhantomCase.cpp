#include "phantom/PhantomCase.hpp"

#include <filesystem>

#include "system/AtomicFile.hpp"

namespace orthosim {

nlohmann::json phantomCaseJson(const Phantom& p) {
  using nlohmann::json;
  return {{"units", "mm"},
          {"name", "phantom " + p.variant.name},
          {"frame", {{"anterior", {-1, 0, 0}}, {"superior", {0, 0, 1}}, {"right", {0, 1, 0}}}},
          {"tissue", {{"skin", "skin.obj"}, {"cavities", {"oral_cavity.stl"}}, {"texture", "skin.jpg"}}},
          {"bones",
           {{{"name", "skull"}, {"surface", "skull.stl"}, {"fixed", true}},
            {{"name", "mandible"}, {"surface", "mandible.stl"}}}},
          {"landmarks", "landmarks.json"},
          {"cuts", {{{"template", "le_fort_1"}, {"bone", "skull"}}, {{"template", "bsso"}, {"bone", "mandible"}}}},
          // Where clinicians look: lips, nose and chin get three and two times the skin density.
          {"meshing",
           {{"refine",
             {{{"landmark", "stomion"}, {"radius_mm", 25}, {"density", 3}},
              {{"landmark", "pronasale"}, {"radius_mm", 18}, {"density", 3}},
              {{"landmark", "soft_pogonion"}, {"radius_mm", 18}, {"density", 2}}}}}},
          // Lips and cheeks slide on the teeth and bone of both jaws. The phantom has no tongue:
          // the floor of its mouth, 35-41 mm below the skin, would in a patient be attached to
          // the mandible, not slide on it; the lips lie within 16 mm, the cheeks within 28.
          {"contact", {{{"bones", {"mandible", "skull"}}, {"range_mm", 15}, {"max_depth_mm", 30}}}},
          {"plan", {{"maxilla", {{"translation_mm", {-5, 0, 0}}}}}}};
}

std::string writePhantomCase(int variant, const std::string& dir) {
  PhantomOptions options;
  options.variant = variant;
  const Phantom phantom = makePhantom(options);
  writePhantom(phantom, dir);
  const std::filesystem::path path = std::filesystem::path(dir) / "case.json";
  writeFileAtomically(path, phantomCaseJson(phantom).dump(2) + "\n");
  return path.string();
}

}  // namespace orthosim
