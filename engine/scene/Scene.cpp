#include "scene/Scene.hpp"

namespace orthosim {

std::optional<int> Scene::fragmentIndex(const std::string& name) const {
  for (size_t i = 0; i < fragments.size(); ++i)
    if (fragments[i].name == name) return static_cast<int>(i);
  return std::nullopt;
}

}  // namespace orthosim
