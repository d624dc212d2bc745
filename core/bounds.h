#pragma once
#include "core/math.h"

namespace tray {

/// Axis-aligned box; default-constructed empty. May be infinite (half-spaces, planes).
struct Bounds3 {
  Vec3 lo{kInfinity}, hi{-kInfinity};
  bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
  bool finite() const { return isFinite(lo) && isFinite(hi); }
  void extend(const Vec3& p) { lo = min(lo, p); hi = max(hi, p); }
  void extend(const Bounds3& b) { lo = min(lo, b.lo); hi = max(hi, b.hi); }
  Vec3 center() const { return 0.5f * (lo + hi); }
  Vec3 diagonal() const { return hi - lo; }
  float surfaceArea() const {
    Vec3 d = diagonal();
    return empty() ? 0.0f : 2.0f * (d.x * d.y + d.y * d.z + d.z * d.x);
  }
};

}  // namespace tray
