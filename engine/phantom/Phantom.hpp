#pragma once
// The built-in synthetic patient: skin envelope, skull, mandible and oral cavity surfaces, landmarks
// and a skin texture, generated deterministically in memory so orthosim runs with no data.
//
// Frame and units: mm; +x posterior, +y patient's right, +z superior (the face looks towards -x);
// the tops of the condyles at z = 0. Symmetric about y = 0 except the asymmetric variant.
// Contract for building the tissue volume (tissue = skin - skull - mandible - oral cavity):
//  - all four surfaces closed, manifold, outward, free of self-intersections;
//  - skull and mandible at least 1 mm apart; both inside the skin, bone at least 4 mm behind the
//    face; the skull is cut to what the envelope holds (the envelope closes above the brows and
//    behind the ears);
//  - the oral cavity crosses the skin between the lips (the mouth slit), runs behind the lips as
//    the vestibule and holds the crowns of both arches (it crosses skull and mandible there).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "image/RgbImage.hpp"
#include "mesh/SurfaceMesh.hpp"

namespace orthosim {

struct Landmark {
  std::string name;
  Eigen::Vector3d position;
};

struct PhantomVariant {
  int index = 0;
  std::string name;  // "class-I", "class-II", "class-III", "asymmetric", "long-face"
  std::string description;
};

// 0 class I (normal), 1 class II (retrognathic mandible), 2 class III (prognathic mandible),
// 3 asymmetric mandible (chin to the patient's right), 4 long face with anterior open bite.
std::vector<PhantomVariant> phantomVariants();

struct PhantomOptions {
  int variant = 0;
  double edgeLength = 1.5;  // mm, target triangle edge of the surfaces (0.5-5)
};

struct Phantom {
  PhantomVariant variant;
  SurfaceMesh skin;        // closed envelope of the soft tissue, with uv (cylindrical, seam at the back)
  SurfaceMesh skull;       // closed: cranium (cut), midface, maxilla with the upper crowns
  SurfaceMesh mandible;    // closed: body, rami, condyles, coronoids, lower crowns
  SurfaceMesh oralCavity;  // closed: the air to remove (mouth slit, vestibule, oral cavity proper)
  // Hard landmarks lie on the skull or mandible surface, except the incisor apices (inside the
  // bone, at the root tips); soft landmarks lie on the skin.
  std::vector<Landmark> hardLandmarks, softLandmarks;
  RgbImage skinTexture;  // 1024 x 1024, addressed by skin.uv (v = 0 at the bottom row)
};

// Throws std::invalid_argument for an unknown variant or an edge length outside [0.5, 5] mm.
Phantom makePhantom(const PhantomOptions& options = {});

// Writes skin.obj (with uv; its texture is skin.jpg beside it, no .mtl), skull.stl, mandible.stl,
// oral_cavity.stl, skin.jpg and landmarks.json ({"hard": {name: [x, y, z]}, "soft": {...}}) into
// `dir`, creating it if needed. Throws std::runtime_error naming the path on failure.
void writePhantom(const Phantom& phantom, const std::string& dir);

}  // namespace orthosim
