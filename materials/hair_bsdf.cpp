#include "materials/hair_bsdf.h"

#include <algorithm>
#include <cmath>

namespace tray {

HairBsdf::HairBsdf(const HairParams& p, const Vec3& tangent, const Vec3& n) : p_(p), n_(n) {
  // The fibre axis, made perpendicular to n. A hair material off a curve (no tangent) gets an
  // arbitrary axis in the tangent plane: the model then shades a fibre lying in the surface.
  Vec3 t = tangent - dot(tangent, n) * n;
  float len = length(t);
  t_ = len > 1e-6f && std::isfinite(len) ? t / len : Frame::fromNormal(n).t;
}

HairBsdf::Placed HairBsdf::at(const Vec3& wo) const {
  Placed f;
  f.x = t_;
  Vec3 perp = wo - dot(wo, t_) * t_;
  float len = length(perp);
  // wo along the fibre: any azimuth will do, take the normal's.
  Vec3 n = dot(n_, wo) < 0 ? -n_ : n_;
  f.z = len > 1e-6f ? perp / len : n;
  f.y = cross(f.z, f.x);
  f.h = std::clamp(dot(n, f.y), -1.0f, 1.0f);
  return f;
}

Color HairBsdf::eval(const Vec3& wo, const Vec3& wi, float& pdf) const {
  const Placed f = at(wo);
  const HairLobe l = lobe(f.h);
  const Vec3 woL = toLocal(f, wo), wiL = toLocal(f, wi);
  pdf = l.pdf(woL, wiL);
  float cosI = std::fabs(dot(wi, n_));
  if (!(cosI > 1e-6f)) return Color(0.0f);
  return l.evalProjected(woL, wiL) / cosI;
}

BsdfSample HairBsdf::sample(const Vec3& wo, float uc, Vec2 u) const {
  const Placed f = at(wo);
  BsdfSample s = lobe(f.h).sample(toLocal(f, wo), uc, u);
  if (!(s.pdf > 0) || !std::isfinite(s.pdf)) return {};
  s.wi = normalize(s.wi.x * f.x + s.wi.y * f.y + s.wi.z * f.z);
  float cosI = std::fabs(dot(s.wi, n_));
  if (!(cosI > 1e-6f)) return {};
  s.f = s.f / cosI;
  s.transmission = dot(s.wi, n_) * dot(wo, n_) < 0;
  return s;
}

}  // namespace tray
