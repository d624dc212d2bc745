#include "lights/area_light.h"

#include "core/light_bounds.h"

namespace tray {

AreaLight AreaLight::triangle(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& front,
                              const Color& Le, bool doubleSided, TriangleSampling sampling) {
  AreaLight l;
  l.sampling_ = sampling;
  l.p0_ = p0;
  l.e1_ = p1 - p0;
  l.e2_ = p2 - p0;
  l.area_ = 0.5f * length(cross(l.e1_, l.e2_));
  l.n_ = length(front) > 0 ? normalize(front) : Vec3(0, 0, 1);
  l.Le_ = Le;
  l.doubleSided_ = doubleSided;
  return l;
}

AreaLight AreaLight::rectangle(const Vec3& corner, const Vec3& ex, const Vec3& ey,
                               const Vec3& front, const Color& Le, bool doubleSided,
                               TriangleSampling sampling) {
  AreaLight l = triangle(corner, corner + ex, corner + ey, front, Le, doubleSided, sampling);
  l.area_ = length(ex) * length(ey);
  l.rectangle_ = true;
  return l;
}

AreaLight AreaLight::shape(const Shape& shape, const Transform& toWorld, const Color& Le,
                           bool doubleSided) {
  AreaLight l;
  l.shape_ = &shape;
  l.toWorld_ = &toWorld;
  l.area_ = shape.area(toWorld);
  l.Le_ = Le;
  l.doubleSided_ = doubleSided;
  return l;
}

float AreaLight::power() const {
  if (!(area_ > 0) || !std::isfinite(area_)) return 0.0f;  // degenerate: never chosen
  const bool twoFaces = doubleSided_ && !shape_;
  return luminance(Le_) * area_ * kPi * (twoFaces ? 2.0f : 1.0f);
}

LightBounds AreaLight::bounds() const {
  if (!(area_ > 0) || !std::isfinite(area_)) return LightBounds::finite({}, n_, 0, 1, 0, false);
  const float L = luminance(Le_);
  if (shape_)
    return LightBounds::finite(toWorld_->bounds(shape_->bounds()), Vec3(0, 0, 1), 0.25f * L * area_,
                               -1.0f, 0.0f, false);
  Bounds3 box;
  box.extend(p0_);
  box.extend(p0_ + e1_);
  box.extend(p0_ + e2_);
  if (rectangle_) box.extend(p0_ + e1_ + e2_);
  return LightBounds::finite(box, n_, L * area_, 1.0f, 0.0f, doubleSided_);
}

LightSample AreaLight::sampleShape(const LightSampleContext& ctx, Vec2 u) const {
  LightSample s;
  std::optional<ShapeSample> ss = shape_->sample({*toWorld_, ctx.p}, u);
  if (!ss || !emitsToward(ss->n, -ss->wi, doubleSided_)) return s;
  s.p = ss->p;
  s.wi = ss->wi;
  s.pdf = ss->pdf;
  s.L = Le_;
  return s;
}

float AreaLight::shapePdf(const LightSampleContext& ctx, const Vec3&, const Vec3& p,
                          const Vec3& n) const {
  return shape_->pdf({*toWorld_, ctx.p}, p, n);
}

}  // namespace tray
