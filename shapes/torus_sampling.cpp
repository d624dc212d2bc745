// Torus sampling for emitters (core/shape.h's sampling interface).
#include <cmath>

#include "shapes/torus.h"

namespace tray {

namespace {

/// Mean axis scale of a similarity transform (as the sphere's worldRadius).
float meanScale(const Transform& toWorld) {
  return (length(toWorld.vector({1, 0, 0})) + length(toWorld.vector({0, 1, 0})) +
          length(toWorld.vector({0, 0, 1}))) /
         3.0f;
}

/// The tube angle theta in [0, 2 pi] with cdf F(theta) = (R theta + r sin theta) / (2 pi R)
/// equal to u: the area element of the torus is r (R + r cos theta) dphi dtheta. F is strictly
/// increasing (R > r), so Newton safeguarded by bisection converges.
double invertTubeCdf(double R, double r, double u) {
  const double target = 2.0 * M_PI * R * u;
  double a = 0.0, b = 2.0 * M_PI, x = 2.0 * M_PI * u;
  for (int i = 0; i < 60; ++i) {
    const double f = R * x + r * std::sin(x) - target;
    if (f > 0)
      b = x;
    else
      a = x;
    const double step = f / (R + r * std::cos(x));
    double next = x - step;
    if (!(next > a && next < b)) next = 0.5 * (a + b);
    if (std::fabs(next - x) < 1e-12) return next;
    x = next;
  }
  return x;
}

}  // namespace

float Torus::area(const Transform& toWorld) const {
  const float s = meanScale(toWorld);
  return 4.0f * kPi * kPi * R_ * r_ * s * s;
}

std::optional<ShapeSample> Torus::sampleArea(const Transform& toWorld, Vec2 u) const {
  const float a = area(toWorld);
  if (!(a > 0) || !std::isfinite(a)) return std::nullopt;
  const float phi = 2.0f * kPi * u.x;
  const float theta = float(invertTubeCdf(R_, r_, u.y));
  const float ct = std::cos(theta), st = std::sin(theta);
  const Vec3 n(ct * std::sin(phi), st, ct * std::cos(phi));
  const float w = R_ + r_ * ct;
  const Vec3 p(w * std::sin(phi), r_ * st, w * std::cos(phi));
  ShapeSample s;
  s.p = toWorld.point(p);
  s.n = normalize(toWorld.normal(n));
  s.pdf = 1.0f / a;
  return s;
}

}  // namespace tray
