#include "phantom/Phantom.hpp"

#include <stdexcept>
#include <string>

#include "phantom/PhantomCavity.hpp"
#include "phantom/PhantomDesign.hpp"
#include "phantom/PhantomLandmarks.hpp"
#include "phantom/PhantomMandible.hpp"
#include "phantom/PhantomSkin.hpp"
#include "phantom/PhantomSkull.hpp"
#include "phantom/SkinTexture.hpp"
#include "phantom/StarSurface.hpp"

namespace orthosim {

std::vector<PhantomVariant> phantomVariants() {
  return {{0, "class-I", "normal occlusion: overjet 2.5 mm, incisors 1.5 mm apart vertically"},
          {1, "class-II", "retrognathic mandible: lower arch and chin 5.5 mm back, overjet about 8 mm"},
          {2, "class-III", "prognathic mandible: lower arch and chin 6 mm forward, lower incisors ahead of the upper"},
          {3, "asymmetric", "mandibular asymmetry: chin and lower midline 7 mm to the patient's right"},
          {4, "long-face", "long face: mandible turned 3 degrees down and back, taller symphysis, anterior open bite"}};
}

Phantom makePhantom(const PhantomOptions& o) {
  const auto variants = phantomVariants();
  if (o.variant < 0 || o.variant >= static_cast<int>(variants.size()))
    throw std::invalid_argument("phantom: unknown variant " + std::to_string(o.variant) + " (0-" +
                                std::to_string(variants.size() - 1) + ")");
  if (!(o.edgeLength >= 0.5 && o.edgeLength <= 5.0))
    throw std::invalid_argument("phantom: edge length " + std::to_string(o.edgeLength) + " mm outside [0.5, 5] mm");
  const phantom::VariantShape shape = phantom::variantShape(o.variant);
  // Arc length tables are built on first use; build them before any parallel loop needs them.
  phantom::archLength(phantom::kUpperArchA, phantom::kUpperArchB, 0.1);
  phantom::archLength(phantom::kLowerArchA, phantom::kLowerArchB, 0.1);

  Phantom p;
  p.variant = variants[o.variant];
  p.skull = phantom::meshStarSurface(phantom::skullSpec(o.edgeLength));

  const phantom::MandibleModel mandible;
  p.mandible = mandible.mesh(o.edgeLength);
  for (int i = 0; i < p.mandible.numVertices(); ++i)
    p.mandible.vertices.col(i) = phantom::mandibleMap(shape, p.mandible.vertices.col(i));

  p.skin = phantom::meshStarSurface(phantom::skinSpec(o.edgeLength));
  phantom::addSkinUv(p.skin);  // from the class I positions: the texture's features stay on the face
  for (int i = 0; i < p.skin.numVertices(); ++i)
    p.skin.vertices.col(i) = phantom::lowerFaceMap(shape, p.skin.vertices.col(i));

  phantom::CavityShape cavity;
  cavity.upperLabialX = phantom::upperCrownTip(0).x() - phantom::upperTeeth()[0].halfThickness;
  cavity.lowerLabialX = phantom::mandibleMap(shape, mandible.outlinePoint(0, mandible.top(0) - 4.0, true)).x();
  cavity.variant = shape;
  cavity.slitZ = phantom::lowerFaceMap(shape, {-96.0, 0.0, phantom::kStomionZ}).z();
  p.oralCavity = phantom::makeOralCavity(cavity, o.edgeLength);

  p.hardLandmarks = phantom::hardLandmarks(mandible, shape);
  p.softLandmarks = phantom::softLandmarks(mandible, shape);
  p.skinTexture = phantom::makeSkinTexture(1024);
  return p;
}

}  // namespace orthosim
