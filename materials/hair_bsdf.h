#pragma once
#include "core/material.h"
#include "core/sampling.h"
#include "materials/bsdf_sample.h"
#include "materials/hair_lobe.h"

namespace tray {

/// HairLobe (Chiang et al. 2016) placed on a fibre in world space. The fibre's axis is the
/// tangent, and its offset h is read from the geometry rather than passed in: the local frame has
/// x along the fibre and z along wo's projection onto the normal plane (so phi_o = pi/2), and
/// h = sin(gamma_o) is the surface normal's component along y = z x x (pbrt-v4 9.9's convention,
/// where a ribbon's h = -1 + 2v runs along its dpdv = z x dpdu). A round curve's normal is the
/// tube's; a flat curve's is made from Embree's v (shapes/curves.cpp), so both read the same.
/// The lobes return f |cos theta_i| for directions over the whole sphere; divided here by the
/// cosine to the shading normal, which the integrator multiplies back.
class HairBsdf {
 public:
  HairBsdf(const HairParams& p, const Vec3& tangent, const Vec3& n);
  /// f(wo, wi) and the pdf of sample() choosing wi.
  Color eval(const Vec3& wo, const Vec3& wi, float& pdf) const;
  /// wi in world space; transmission: wi on the far side of n from wo.
  BsdfSample sample(const Vec3& wo, float uc, Vec2 u) const;

 private:
  struct Placed {
    Vec3 x, y, z;
    float h;
  };
  Placed at(const Vec3& wo) const;
  HairLobe lobe(float h) const {
    return HairLobe(h, p_.ior, p_.sigmaA, p_.betaM, p_.betaN, p_.alpha);
  }
  static Vec3 toLocal(const Placed& f, const Vec3& w) {
    return {dot(w, f.x), dot(w, f.y), dot(w, f.z)};
  }
  HairParams p_;
  Vec3 t_, n_;
};

}  // namespace tray
