#pragma once
#include "core/sampling.h"
#include "lights/light_sample.h"

namespace tray {

/// An emissive analytic sphere, emitting outwards. From outside it is sampled uniformly in the
/// cone of directions it subtends (pbrt-v4 6.2.4): every sample hits it, and the pdf is the
/// constant 1 / (2 pi (1 - cos theta_max)). Points inside get no light samples (the BSDF
/// sampling still finds the inside, which does not emit).
struct SphereLight {
  Vec3 center;
  float radius = 1;
  Color Le;

  float power() const { return luminance(Le) * 4.0f * kPi * radius * radius * kPi; }
  /// 1 - cos theta_max of the cone seen from ref, computed without cancellation; <= 0 inside.
  float oneMinusCosMax(const Vec3& ref) const {
    float dc2 = lengthSquared(center - ref), r2 = radius * radius;
    if (dc2 <= r2) return 0.0f;
    float sin2 = r2 / dc2;
    return sin2 / (1.0f + std::sqrt(1.0f - sin2));
  }
  LightSample sample(const Vec3& ref, Vec2 u) const {
    LightSample s;
    float omc = oneMinusCosMax(ref);
    if (!(omc > 0)) return s;
    Vec3 toCenter = center - ref;
    float dc = length(toCenter);
    Frame f = Frame::fromNormal(toCenter / dc);
    Vec3 local = sampleUniformCone(u, omc);
    s.wi = normalize(f.toWorld(local));
    // Nearest intersection of the sampled direction with the sphere.
    float cosT = local.z, sin2T = std::max(0.0f, 1.0f - cosT * cosT);
    float ds = dc * cosT - std::sqrt(std::max(0.0f, radius * radius - dc * dc * sin2T));
    s.p = ref + ds * s.wi;
    s.pdf = uniformConePdf(omc);
    s.L = Le;
    return s;
  }
  float pdf(const Vec3& ref) const {
    float omc = oneMinusCosMax(ref);
    return omc > 0 ? uniformConePdf(omc) : 0.0f;
  }
};

}  // namespace tray
