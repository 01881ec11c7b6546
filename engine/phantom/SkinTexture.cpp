#include "phantom/SkinTexture.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "math/Angles.hpp"
#include "phantom/ImplicitShapes.hpp"
#include "phantom/PhantomDesign.hpp"
#include "phantom/PhantomSkin.hpp"

namespace orthosim::phantom {
namespace {

// Hash-based value noise in [0, 1]: fixed, so the texture is identical on every run.
double hashNoise(int x, int y) {
  uint32_t h = static_cast<uint32_t>(x) * 374761393u + static_cast<uint32_t>(y) * 668265263u;
  h = (h ^ (h >> 13)) * 1274126177u;
  return ((h ^ (h >> 16)) & 0xffffu) / 65535.0;
}

double valueNoise(double x, double y) {
  const int ix = static_cast<int>(std::floor(x)), iy = static_cast<int>(std::floor(y));
  const double fx = x - ix, fy = y - iy;
  const double sx = fx * fx * (3 - 2 * fx), sy = fy * fy * (3 - 2 * fy);
  const double a = hashNoise(ix, iy), b = hashNoise(ix + 1, iy), c = hashNoise(ix, iy + 1),
               d = hashNoise(ix + 1, iy + 1);
  return (a + (b - a) * sx) * (1 - sy) + (c + (d - c) * sx) * sy;
}

// Position on the class I face for texture coordinates (u, v): the lateral offset y along the
// front and the height z, which is how the features below are placed.
void faceCoords(double u, double v, double& y, double& z) {
  const double angle = (u - 0.5) * 2 * kPi;  // 0 straight ahead
  y = 66.0 * std::sin(angle);                // about the face's distance from the uv axis
  z = kSkinBottomZ + v * (kSkinTopZ - kSkinBottomZ);
}

}  // namespace

RgbImage makeSkinTexture(int size) {
  RgbImage img;
  img.width = img.height = size;
  img.pixels.resize(static_cast<size_t>(size) * size * 3);
  const double skin[3] = {226, 178, 152}, lip[3] = {192, 88, 96}, brow[3] = {96, 70, 52};
  for (int row = 0; row < size; ++row)
    for (int col = 0; col < size; ++col) {
      const double u = (col + 0.5) / size, v = 1.0 - (row + 0.5) / size;
      double y, z;
      faceCoords(u, v, y, z);
      const bool front = std::abs(u - 0.5) < 0.25;
      // Lips: vermilion above and below the stomion, thinning to the mouth corners.
      const double across = std::clamp(1 - std::pow(y / (kMouthHalfWidth + 1), 2), 0.0, 1.0);
      const double dz = z - kStomionZ;
      const double upper = 7.0 * std::sqrt(across) * (1 - 0.25 * std::exp(-y * y / 20)),
                   lower = 9.0 * std::sqrt(across);
      double lipW = 0;
      if (front && across > 0)
        lipW = dz >= 0 ? smoothstep(upper, upper - 1.5, dz) : smoothstep(-lower, -lower + 1.5, dz);
      // Brows: an arc above each orbit.
      double browW = 0;
      if (front) {
        const double ay = std::abs(y), centre = 41.0 - 0.004 * (ay - 30) * (ay - 30);
        browW = smoothstep(3.5, 2.0, std::abs(z - centre)) * smoothstep(12, 16, ay) * smoothstep(48, 42, ay);
      }
      // Faint warmth on the cheeks.
      const double cheek =
          front ? 0.07 * std::exp(-(std::pow((std::abs(y) - 42) / 14, 2) + std::pow((z + 12) / 16, 2))) : 0;
      const double n = 0.6 * valueNoise(col / 6.0, row / 6.0) + 0.4 * valueNoise(col / 23.0, row / 23.0) - 0.5;
      for (int k = 0; k < 3; ++k) {
        double c = skin[k] * (1 - cheek * (k == 0 ? -0.2 : 0.6));
        c += (lip[k] - c) * lipW;
        c += (brow[k] - c) * 0.8 * browW;
        c *= 1 + 0.06 * n;
        img.pixels[(static_cast<size_t>(row) * size + col) * 3 + k] =
            static_cast<unsigned char>(std::clamp(c, 0.0, 255.0));
      }
    }
  return img;
}

}  // namespace orthosim::phantom
