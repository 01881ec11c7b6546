#include "render/CaseView.hpp"

#include "render/CaseBones.hpp"
#include "render/ImageFile.hpp"
#include "render/RenderError.hpp"

namespace orthosim::render {

RgbImage caseTexture(const CaseSpec& spec) {
  if (spec.texture.empty()) return {};
  try {
    return readImage(spec.texture);
  } catch (const RenderError& e) {
    throw RenderError(spec.file + ": tissue.texture: " + e.what());
  }
}

void setCase(Renderer& renderer, const CaseModel& model, const RgbImage& texture) {
  if (model.tissue.skin.numTriangles() == 0) throw RenderError(model.spec.file + ": the case has no skin to render");
  renderer.setSkin(model.tissue.skin, texture);
  renderer.setBones(caseBonePieces(model));
}

void setCaseState(Renderer& renderer, const CaseModel& model, const SimState& state) {
  renderer.updateSkin(model.skinEmbedding.apply(state.x));
  renderer.setFragmentPoses(state.fragments);
}

}  // namespace orthosim::render
