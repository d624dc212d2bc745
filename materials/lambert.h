#pragma once
#include "core/sampling.h"
#include "materials/bsdf_sample.h"
// eval, pdf and sample, written once for scalar code and the SIMD stages.
#include "materials/lambert_lanes.h"

namespace tray {

/// Lambert's ideal diffuse reflection, f = albedo / pi, on the side of wo.
struct LambertLobe {
  Color albedo;
  Color eval(const Vec3& wo, const Vec3& wi) const {
    float unused;
    return lambertEvalPdf(albedo, wo.z, wi.z, unused);
  }
  float pdf(const Vec3& wo, const Vec3& wi) const {
    float p;
    lambertEvalPdf(albedo, wo.z, wi.z, p);
    return p;
  }
  BsdfSample sample(const Vec3& wo, Vec2 u) const {
    const LambertSampleOf<Vec3> l = lambertSample(albedo, wo.z, u);
    BsdfSample s;
    s.wi = l.wi;
    s.pdf = l.pdf;
    s.f = l.f;
    return s;
  }
};

}  // namespace tray
