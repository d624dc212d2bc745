// Sphere sampling for emitters (core/shape.h's sampling interface).
#include "core/sampling.h"
#include "shapes/sphere.h"

namespace tray {

float Sphere::worldRadius(const Transform& toWorld) const {
  float s = (length(toWorld.vector({1, 0, 0})) + length(toWorld.vector({0, 1, 0})) +
             length(toWorld.vector({0, 0, 1}))) /
            3.0f;
  return radius_ * s;
}

float Sphere::area(const Transform& toWorld) const {
  const float r = worldRadius(toWorld);
  return 4.0f * kPi * r * r;
}

std::optional<ShapeSample> Sphere::sampleArea(const Transform& toWorld, Vec2 u) const {
  ShapeSample s;
  s.n = sampleUniformSphere(u);
  s.p = toWorld.point(Vec3(0.0f)) + worldRadius(toWorld) * s.n;
  s.pdf = 1.0f / area(toWorld);
  return s;
}

float Sphere::oneMinusCosMax(const Vec3& c, float r, const Vec3& ref) {
  float dc2 = lengthSquared(c - ref), r2 = r * r;
  if (dc2 <= r2) return 0.0f;
  float sin2 = r2 / dc2;
  return sin2 / (1.0f + std::sqrt(1.0f - sin2));
}

std::optional<ShapeSample> Sphere::sample(const ShapeSampleContext& ctx, Vec2 u) const {
  const Vec3 center = ctx.toWorld.point(Vec3(0.0f));
  const float radius = worldRadius(ctx.toWorld);
  const float omc = oneMinusCosMax(center, radius, ctx.p);
  if (!(omc > 0)) return std::nullopt;
  ShapeSample s;
  Vec3 toCenter = center - ctx.p;
  float dc = length(toCenter);
  Frame f = Frame::fromNormal(toCenter / dc);
  Vec3 local = sampleUniformCone(u, omc);
  s.wi = normalize(f.toWorld(local));
  // Nearest intersection of the sampled direction with the sphere.
  float cosT = local.z, sin2T = std::max(0.0f, 1.0f - cosT * cosT);
  float ds = dc * cosT - std::sqrt(std::max(0.0f, radius * radius - dc * dc * sin2T));
  s.p = ctx.p + ds * s.wi;
  s.n = normalize(s.p - center);
  s.pdf = uniformConePdf(omc);
  return s;
}

float Sphere::pdf(const ShapeSampleContext& ctx, const Vec3&, const Vec3&) const {
  const float omc = oneMinusCosMax(ctx.toWorld.point(Vec3(0.0f)), worldRadius(ctx.toWorld), ctx.p);
  return omc > 0 ? uniformConePdf(omc) : 0.0f;
}

}  // namespace tray
