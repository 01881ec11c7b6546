#include "volume/SyntheticCt.hpp"

#include <cmath>
#include <random>

#include "volume/SurfaceVoxels.hpp"

namespace orthosim {
namespace {

// A bright band along the streak's line flanked by dark ones (beam hardening and photon starvation
// beside metal), in the slice through the metal, fading with distance from it.
float streakAt(const MetalStreak& m, const Eigen::Vector3d& p, double sliceHalf) {
  const Eigen::Vector3d d = p - m.at;
  if (std::abs(d.z()) > sliceHalf) return 0;
  const Eigen::Vector3d along = Eigen::Vector3d(m.towards.x(), m.towards.y(), 0).normalized();
  const double t = d.dot(along);
  if (std::abs(t) > m.lengthMm || std::abs(t) < m.radiusMm) return 0;
  const double off = (Eigen::Vector3d(d.x(), d.y(), 0) - t * along).norm() / m.widthMm;
  const double fade = 1.0 - std::abs(t) / m.lengthMm;
  // Mexican-hat profile: bright on the line, dark beside it.
  return float(m.amplitude * fade * (1 - off * off) * std::exp(-0.5 * off * off));
}

}  // namespace

CtVolume syntheticCt(const SyntheticCtInput& input) {
  CtVolume ct = input.grid;
  ct.values.assign(size_t(ct.count()), input.background);
  for (const CtLayer& layer : input.layers) {
    const std::vector<float> share = enclosedShare(*layer.surface, ct, 2);
    for (size_t v = 0; v < share.size(); ++v) ct.values[v] += share[v] * (layer.value - ct.values[v]);
  }
  std::mt19937 random(input.seed);
  std::normal_distribution<float> noise(0.f, input.noiseSigma);
  if (input.noiseSigma > 0)
    for (float& v : ct.values) v += noise(random);
  const double sliceHalf = 0.5 * ct.spacing()[2] + 1e-9;
  for (const MetalStreak& m : input.metal)
    for (int k = 0; k < ct.size[2]; ++k)
      for (int j = 0; j < ct.size[1]; ++j)
        for (int i = 0; i < ct.size[0]; ++i) {
          const Eigen::Vector3d p = ct.position(Eigen::Vector3d(i, j, k));
          float& v = ct.values[size_t(ct.index(i, j, k))];
          if ((p - m.at).norm() <= m.radiusMm)
            v = m.metal;
          else
            v += streakAt(m, p, sliceHalf);
        }
  return ct;
}

}  // namespace orthosim
