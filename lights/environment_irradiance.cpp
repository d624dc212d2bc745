#include "lights/environment_irradiance.h"

#include <cmath>

namespace tray {
namespace {

/// The nine real spherical harmonics Y_00 .. Y_22 at unit direction d (Ramamoorthi & Hanrahan
/// 2001, eq. 3, in their x, y, z order).
std::array<float, 9> basis(const Vec3& d) {
  const float x = d.x, y = d.y, z = d.z;
  return {0.282095f,
          0.488603f * y,
          0.488603f * z,
          0.488603f * x,
          1.092548f * x * y,
          1.092548f * y * z,
          0.315392f * (3 * z * z - 1),
          1.092548f * x * z,
          0.546274f * (x * x - y * y)};
}

}  // namespace

EnvironmentIrradiance::EnvironmentIrradiance(const Light& light, int width) {
  const int height = std::max(width / 2, 1);
  std::array<double, 27> sum{};
  for (int j = 0; j < height; ++j) {
    const double theta = kPi * (j + 0.5) / height;
    const double dOmega = std::sin(theta) * (kPi / height) * (2 * kPi / width);
    for (int i = 0; i < width; ++i) {
      const double phi = 2 * kPi * (i + 0.5) / width;
      const Vec3 d(float(std::sin(theta) * std::cos(phi)), float(std::cos(theta)),
                   float(std::sin(theta) * std::sin(phi)));
      const Color L = light.Le(d);
      const std::array<float, 9> y = basis(d);
      for (int k = 0; k < 9; ++k) {
        sum[3 * k] += L.x * y[k] * dOmega;
        sum[3 * k + 1] += L.y * y[k] * dOmega;
        sum[3 * k + 2] += L.z * y[k] * dOmega;
      }
    }
  }
  // The clamped cosine's band factors A_0 = pi, A_1 = 2 pi / 3, A_2 = pi / 4 (eq. 8).
  const double band[9] = {kPi,          2 * kPi / 3,  2 * kPi / 3,  2 * kPi / 3, kPi / 4,
                          kPi / 4,      kPi / 4,      kPi / 4,      kPi / 4};
  for (int k = 0; k < 9; ++k)
    coefficients_[size_t(k)] = Color(float(sum[3 * k] * band[k]), float(sum[3 * k + 1] * band[k]),
                                     float(sum[3 * k + 2] * band[k]));
}

Color EnvironmentIrradiance::irradiance(const Vec3& n) const {
  const std::array<float, 9> y = basis(n);
  Color E(0.0f);
  for (size_t k = 0; k < 9; ++k) E += coefficients_[k] * y[k];
  // Nine bands ring slightly below zero opposite a bright, small source: no negative light.
  return {std::max(E.x, 0.0f), std::max(E.y, 0.0f), std::max(E.z, 0.0f)};
}

}  // namespace tray
