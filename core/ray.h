#pragma once
#include <cstdint>
#include <cstring>

#include "core/math.h"

namespace tray {

struct Ray {
  Vec3 o, d;  ///< origin and direction (direction need not be unit length)
  float tmin = 0.0f;
  float tmax = kInfinity;
};

/// Offsets a surface point along its geometric normal by a few float ULPs scaled with the
/// point's magnitude, so a ray leaving it never re-hits the same surface at any scene scale.
/// Wächter & Binder, "A Fast and Robust Method for Avoiding Self-Intersection", Ray Tracing
/// Gems ch. 6 (2019). `n` must point to the side the new ray leaves towards.
inline Vec3 offsetRayOrigin(const Vec3& p, const Vec3& n) {
  constexpr float kOrigin = 1.0f / 32.0f, kFloatScale = 1.0f / 65536.0f, kIntScale = 256.0f;
  Vec3 out;
  for (int i = 0; i < 3; ++i) {
    int32_t offset = static_cast<int32_t>(kIntScale * n[i]);
    int32_t bits;
    float pi = p[i];
    std::memcpy(&bits, &pi, sizeof bits);
    bits += (pi < 0) ? -offset : offset;
    float moved;
    std::memcpy(&moved, &bits, sizeof moved);
    out[i] = std::fabs(pi) < kOrigin ? pi + kFloatScale * n[i] : moved;
  }
  return out;
}

/// A ray leaving surface point p (geometric normal ng) in direction d, offset to the side d goes.
inline Ray spawnRay(const Vec3& p, const Vec3& ng, const Vec3& d) {
  Vec3 n = dot(d, ng) >= 0 ? ng : -ng;
  return Ray{offsetRayOrigin(p, n), d, 0.0f, kInfinity};
}

/// A shadow ray from p towards target, stopping just before the target point.
inline Ray spawnRayTo(const Vec3& p, const Vec3& ng, const Vec3& target) {
  Vec3 d = target - p;
  Vec3 n = dot(d, ng) >= 0 ? ng : -ng;
  Vec3 o = offsetRayOrigin(p, n);
  return Ray{o, target - o, 0.0f, 1.0f - 1e-4f};
}

}  // namespace tray
