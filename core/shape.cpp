#include "core/shape.h"

#include <cmath>

namespace tray {

float areaScale(const Transform& toWorld, const Vec3& n) {
  const auto& m = toWorld.m.m;
  const float det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                    m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                    m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  return std::fabs(det) * length(toWorld.normal(n));
}

std::optional<ShapeSample> Shape::sample(const ShapeSampleContext& ctx, Vec2 u) const {
  std::optional<ShapeSample> s = sampleArea(ctx.toWorld, u);
  if (!s) return std::nullopt;
  const Vec3 d = s->p - ctx.p;
  const float dist2 = lengthSquared(d);
  if (!(dist2 > 0)) return std::nullopt;
  s->wi = d / std::sqrt(dist2);
  const float cosL = std::fabs(dot(s->n, s->wi));
  if (!(cosL > 0)) return std::nullopt;
  s->pdf *= dist2 / cosL;  // dA = d^2 / |cos| dw
  if (!std::isfinite(s->pdf)) return std::nullopt;
  return s;
}

float Shape::pdf(const ShapeSampleContext& ctx, const Vec3& p, const Vec3& n) const {
  const float a = area(ctx.toWorld);
  const Vec3 d = p - ctx.p;
  const float dist2 = lengthSquared(d);
  if (!(a > 0) || !(dist2 > 0)) return 0.0f;
  const float cosL = std::fabs(dot(n, d)) / std::sqrt(dist2);
  return cosL > 0 ? dist2 / (cosL * a) : 0.0f;
}

}  // namespace tray
