#pragma once
#include "core/math.h"

namespace tray {

/// One sampled scattering direction, in the lobe's local frame (+z = shading normal).
struct BsdfSample {
  Vec3 wi;
  Color f;             ///< BSDF value (for delta lobes: the delta's coefficient)
  float pdf = 0;       ///< solid-angle pdf, or the discrete probability of a delta lobe
  float etaScale = 1;  ///< (n_i / n_t)^2 crossing a refractive interface, else 1
  bool delta = false;
  bool transmission = false;
  bool valid() const { return pdf > 0; }
  /// f |cos| / pdf, the throughput multiplier; only while wi is in the local frame.
  Color weight() const { return f * (std::fabs(wi.z) / pdf); }
};

inline float cosTheta(const Vec3& w) {
  return w.z;
}
inline float absCosTheta(const Vec3& w) {
  return std::fabs(w.z);
}
inline bool sameHemisphere(const Vec3& a, const Vec3& b) {
  return a.z * b.z > 0;
}

}  // namespace tray
