#pragma once
// A case in a renderer: what a server session or a command does after building a CaseModel and
// after each solve.
#include "image/RgbImage.hpp"
#include "render/Renderer.hpp"
#include "scene/CaseModel.hpp"
#include "solver/SimState.hpp"

namespace orthosim::render {

// The image CaseSpec::texture names, or an empty image when the case names none. Throws
// RenderError naming the file when it is missing or not a JPEG or PNG image.
RgbImage caseTexture(const CaseSpec& spec);

// Uploads the case's rest skin (with `texture`, which needs the skin's uv) and its bone pieces.
// Throws RenderError when the case has no skin.
void setCase(Renderer& renderer, const CaseModel& model, const RgbImage& texture);

// A solved state of the case: the deformed skin (positions only) and the fragments' poses.
void setCaseState(Renderer& renderer, const CaseModel& model, const SimState& state);

}  // namespace orthosim::render
