// Rays leaving the lights (pbrt-v4 12.2-12.6, SampleLe and PDF_Le), for the estimators that
// trace paths from the lights: photon mapping (integrators/sppm) and bidirectional path
// tracing (integrators/bdpt). One file for the four kinds: the same three warps (a position,
// a cosine lobe, a disk facing the scene) serve them all.
#include <cmath>

#include "core/sampling.h"
#include "lights/area_light.h"
#include "lights/environment_light.h"
#include "lights/image_environment_light.h"
#include "lights/punctual_light.h"

namespace tray {
namespace {

/// A ray arriving from direction `from` (unit, pointing away from the scene) through the
/// world's bounding disk perpendicular to it, its origin uniform on the disk, placed a radius
/// out: every ray from that direction that can meet the scene crosses the disk.
Ray diskRay(const Vec3& from, Vec2 u, const WorldSphere& world) {
  const Frame f = Frame::fromNormal(-from);
  const Vec2 d = sampleUniformDiskConcentric(u);
  Ray r;
  r.o = world.center + world.radius * (f.toWorld(Vec3(d.x, d.y, 0.0f)) + from);
  r.d = -from;
  return r;
}

float diskPdf(const WorldSphere& world) { return 1.0f / (kPi * world.radius * world.radius); }

}  // namespace

LightLeSample AreaLight::sampleLe(Vec2 u1, Vec2 u2, const WorldSphere&) const {
  LightLeSample s;
  if (!(area_ > 0) || !std::isfinite(area_) || isBlack(Le_)) return s;
  Vec3 p, n;
  bool flip = false;
  if (shape_) {
    const std::optional<ShapeSample> ss = shape_->sampleArea(*toWorld_, u1);
    if (!ss) return s;
    p = ss->p, n = ss->n;
  } else {
    if (rectangle_) {  // uniform over the rectangle
      p = p0_ + u1.x * e1_ + u1.y * e2_;
    } else {
      const Vec3 b = sampleUniformTriangle(u1);
      p = p0_ + b.y * e1_ + b.z * e2_;
    }
    n = n_;
    if (doubleSided_) {  // either face with probability 1/2; u2.x reused
      flip = u2.x < 0.5f;
      u2.x = flip ? 2.0f * u2.x : 2.0f * u2.x - 1.0f;
      u2.x = std::min(u2.x, 0.99999994f);
      if (flip) n = -n;
    }
  }
  const Vec3 local = sampleCosineHemisphere(u2);
  if (!(local.z > 0)) return s;
  s.ray.o = p;
  s.ray.d = normalize(Frame::fromNormal(n).toWorld(local));
  s.n = n;
  s.L = Le_;
  s.pdfPos = 1.0f / area_;
  s.pdfDir = cosineHemispherePdf(local.z) * (doubleSided_ && !shape_ ? 0.5f : 1.0f);
  return s;
}

LightLePdf AreaLight::pdfLe(const Vec3&, const Vec3& n, const Vec3& w, const WorldSphere&) const {
  LightLePdf pdf;
  if (!(area_ > 0) || !std::isfinite(area_)) return pdf;
  const bool twoSided = doubleSided_ && !shape_;
  const float c = dot(n, w);
  if (!twoSided && !(c > 0)) return pdf;
  pdf.pos = 1.0f / area_;
  pdf.dir = std::fabs(c) * (1.0f / kPi) * (twoSided ? 0.5f : 1.0f);
  return pdf;
}

LightLeSample PunctualLight::sampleLe(Vec2 u1, Vec2 u2, const WorldSphere& world) const {
  LightLeSample s;
  switch (desc_.type) {
    case PunctualLightDesc::Type::kPoint:
      s.ray.o = desc_.position;
      s.ray.d = normalize(sampleUniformSphere(u1));
      s.L = desc_.intensity;
      s.pdfPos = 1.0f, s.pdfDir = kUniformSpherePdf;
      break;
    case PunctualLightDesc::Type::kSpot: {
      const float omc = 1.0f - lanes_.cosOuter;
      if (!(omc > 0)) return s;
      const Vec3 local = sampleUniformCone(u1, omc);
      s.ray.o = desc_.position;
      s.ray.d = normalize(Frame::fromNormal(desc_.direction).toWorld(local));
      s.L = desc_.intensity * spotFalloffOf(local.z, lanes_.cosOuter, lanes_.cosInner);
      s.pdfPos = 1.0f, s.pdfDir = uniformConePdf(omc);
      break;
    }
    case PunctualLightDesc::Type::kDirectional:
      s.ray = diskRay(-desc_.direction, u2, world);
      s.L = desc_.intensity;
      s.pdfPos = diskPdf(world), s.pdfDir = 1.0f;
      break;
  }
  return s;
}

LightLePdf PunctualLight::pdfLe(const Vec3&, const Vec3&, const Vec3& w,
                                const WorldSphere& world) const {
  LightLePdf pdf;
  switch (desc_.type) {
    case PunctualLightDesc::Type::kPoint:
      pdf.dir = kUniformSpherePdf;
      break;
    case PunctualLightDesc::Type::kSpot:
      if (dot(w, desc_.direction) >= lanes_.cosOuter && lanes_.cosOuter < 1.0f)
        pdf.dir = uniformConePdf(1.0f - lanes_.cosOuter);
      break;
    case PunctualLightDesc::Type::kDirectional:
      pdf.pos = diskPdf(world);
      break;
  }
  return pdf;
}

LightLeSample EnvironmentLight::sampleLe(Vec2 u1, Vec2 u2, const WorldSphere& world) const {
  LightLeSample s;
  const Vec3 from = normalize(sampleUniformSphere(u1));
  s.ray = diskRay(from, u2, world);
  s.L = Le_;
  s.pdfPos = diskPdf(world), s.pdfDir = kUniformSpherePdf;
  return s;
}

LightLePdf EnvironmentLight::pdfLe(const Vec3&, const Vec3&, const Vec3&,
                                   const WorldSphere& world) const {
  return {diskPdf(world), kUniformSpherePdf};
}

LightLeSample ImageEnvironmentLight::sampleLe(Vec2 u1, Vec2 u2, const WorldSphere& world) const {
  LightLeSample s;
  const LightSample dir = sample(LightSampleContext{}, u1);
  if (!dir.valid()) return s;
  s.ray = diskRay(dir.wi, u2, world);
  s.L = dir.L;
  s.pdfPos = diskPdf(world), s.pdfDir = dir.pdf;
  return s;
}

LightLePdf ImageEnvironmentLight::pdfLe(const Vec3&, const Vec3&, const Vec3& w,
                                        const WorldSphere& world) const {
  return {diskPdf(world), pdf(LightSampleContext{}, -w, Vec3(), Vec3())};
}

}  // namespace tray
