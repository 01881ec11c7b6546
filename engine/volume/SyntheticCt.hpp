#pragma once
// A CT made from closed surfaces, for tests and benchmarks that need a scan with known anatomy:
// each layer (skin, cavities, bones) sets the grey value of what it encloses, over the layers
// before it, with the partial volume of voxels its surface cuts; then the scanner's noise, and the
// streaks metal (a filling, a bracket) throws across its slice.
#include <Eigen/Core>
#include <vector>

#include "mesh/SurfaceMesh.hpp"
#include "volume/CtVolume.hpp"

namespace orthosim {

struct CtLayer {
  const SurfaceMesh* surface = nullptr;
  float value = 0;  // Hounsfield units inside
};

struct MetalStreak {
  Eigen::Vector3d at = Eigen::Vector3d::Zero();        // the metal's centre, LPS mm
  Eigen::Vector3d towards = Eigen::Vector3d::UnitX();  // the streak's direction (within the slice)
  double radiusMm = 1.5;                               // the metal ball
  float metal = 8000;                                  // its value
  float amplitude = 1200;                              // the streak's light and dark bands
  double widthMm = 0.7;                                // each band's half width
  double lengthMm = 60;                                // how far the streak runs each way
};

struct SyntheticCtInput {
  CtVolume grid;             // placement only (size, directions, origin)
  float background = -1000;  // air
  std::vector<CtLayer> layers;
  float noiseSigma = 20;  // Gaussian, HU
  unsigned seed = 1;
  std::vector<MetalStreak> metal;
};

CtVolume syntheticCt(const SyntheticCtInput& input);

}  // namespace orthosim
