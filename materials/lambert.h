#pragma once
#include "core/sampling.h"
#include "materials/bsdf_sample.h"

namespace tray {

/// Lambert's ideal diffuse reflection, f = albedo / pi, on the side of wo.
struct LambertLobe {
  Color albedo;
  Color eval(const Vec3& wo, const Vec3& wi) const {
    return sameHemisphere(wo, wi) ? albedo * (1.0f / kPi) : Color(0.0f);
  }
  float pdf(const Vec3& wo, const Vec3& wi) const {
    return sameHemisphere(wo, wi) ? cosineHemispherePdf(absCosTheta(wi)) : 0.0f;
  }
  BsdfSample sample(const Vec3& wo, Vec2 u) const {
    BsdfSample s;
    s.wi = sampleCosineHemisphere(u);
    s.wi.z = wo.z < 0 ? -s.wi.z : s.wi.z;  // a select: the side is random per bounce
    s.pdf = cosineHemispherePdf(absCosTheta(s.wi));
    s.f = albedo * (1.0f / kPi);
    return s;
  }
};

}  // namespace tray
