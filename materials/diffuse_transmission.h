#pragma once
// KHR_materials_diffuse_transmission's lobe for scalar code: the functions of
// materials/diffuse_transmission_lanes.h over one float.
#include "materials/bsdf_sample.h"
#include "materials/diffuse_transmission_lanes.h"

namespace tray {

/// Lambert reflection (albedo `reflect` = (1 - diffuseTransmission) baseColor) on wo's side
/// plus Lambert transmission (albedo `transmit` = diffuseTransmission x
/// diffuseTransmissionColor) on the far side, thin-walled: the transmitted ray leaves from the
/// far side with no change of medium (docs/materials-extensions.md).
class DiffuseTransmissionLobe {
 public:
  DiffuseTransmissionLobe(const Color& reflect, const Color& transmit)
      : reflect_(reflect),
        transmit_(transmit),
        pTransmit_(diffuseTransmissionProb(reflect, transmit)) {}
  const Color& reflect() const { return reflect_; }
  const Color& transmit() const { return transmit_; }
  Color eval(const Vec3& wo, const Vec3& wi, float& pdf) const {
    return diffuseTransmissionEvalPdf(reflect_, transmit_, pTransmit_, wo.z, wi.z, pdf);
  }
  Color eval(const Vec3& wo, const Vec3& wi) const {
    float unused;
    return eval(wo, wi, unused);
  }
  float pdf(const Vec3& wo, const Vec3& wi) const {
    float p;
    eval(wo, wi, p);
    return p;
  }
  BsdfSample sample(const Vec3& wo, float uc, Vec2 u) const {
    const DiffuseTransmissionSampleOf<Vec3> d =
        diffuseTransmissionSample(reflect_, transmit_, pTransmit_, wo.z, uc, u);
    BsdfSample s;
    s.wi = d.wi, s.f = d.f, s.pdf = d.pdf;
    s.transmission = d.transmitted;
    if (!(s.pdf > 0) || wo.z == 0) s.pdf = 0;
    return s;
  }

 private:
  Color reflect_, transmit_;
  float pTransmit_;
};

}  // namespace tray
