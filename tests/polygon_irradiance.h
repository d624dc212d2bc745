#pragma once
// Closed-form irradiance from a uniformly emitting polygon, for tests of area lights.
#include <cmath>
#include <vector>

#include "core/math.h"

namespace tray::test {

/// Irradiance at x (unit normal n) from a polygon of unit radiance, all of it above x's
/// horizon: Lambert's formula E = 1/2 sum_i angle(u_i, u_i+1) n . unit(u_i x u_i+1)
/// (pbrt-v4 4.5.1's polygon form factor; Arvo 1995), in double.
inline double polygonIrradiance(const Vec3& x, const Vec3& n, const std::vector<Vec3>& poly) {
  double sum = 0;
  for (size_t i = 0; i < poly.size(); ++i) {
    double u[3], v[3];
    const Vec3 &a = poly[i], &b = poly[(i + 1) % poly.size()];
    for (int k = 0; k < 3; ++k) u[k] = a[k] - x[k], v[k] = b[k] - x[k];
    double lu = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    double lv = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    double c[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    double lc = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    double angle = std::acos((u[0] * v[0] + u[1] * v[1] + u[2] * v[2]) / (lu * lv));
    sum += 0.5 * angle * (n.x * c[0] + n.y * c[1] + n.z * c[2]) / lc;
  }
  return std::fabs(sum);
}

}  // namespace tray::test
