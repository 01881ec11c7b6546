#pragma once
// The envelope of a set of predicted skins about a nominal one (what a prediction band shows): at each vertex the
// least and greatest signed offset of the variants from the nominal skin along its vertex normal
// (positive outward: tissue fuller). Offsets along the surface are not counted: a vertex that
// slides over the face leaves the face where it was, which is what a surgeon compares.
#include <Eigen/Core>
#include <vector>

#include "mesh/SurfaceMesh.hpp"

namespace orthosim {

struct SkinEnvelope {
  SurfaceMesh nominal;
  Eigen::Matrix3Xd normals;   // unit vertex normals of the nominal skin
  Eigen::VectorXd low, high;  // mm per vertex; low <= 0 <= high (the nominal is in the set)

  Eigen::VectorXd width() const { return high - low; }
  SurfaceMesh lowSurface() const;   // nominal + low along the normal
  SurfaceMesh highSurface() const;  // nominal + high along the normal
};

// Starts with the nominal alone (both offsets 0); add() widens it by one variant.
SkinEnvelope skinEnvelope(const SurfaceMesh& nominal);
// Throws std::invalid_argument when the variant is not the nominal skin deformed (other vertex
// count or triangles) or has a non-finite vertex.
void addToEnvelope(SkinEnvelope& envelope, const SurfaceMesh& variant);

}  // namespace orthosim
