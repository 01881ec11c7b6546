#pragma once
// The phantom's skin texture: a skin tone with faint deterministic mottling, reddish lips and
// darker brows where the skin's uv (PhantomSkin.hpp) puts them, so a render reads as a face.
#include "image/RgbImage.hpp"

namespace orthosim::phantom {

RgbImage makeSkinTexture(int size = 1024);

}  // namespace orthosim::phantom
