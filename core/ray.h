#pragma once
#include <cstdint>

#include "core/math.h"
#include "core/ray_lanes.h"

namespace tray {

/// How an accelerator treats surfaces of alphaMode BLEND (docs/scene-format.md, "Alpha"). MASK
/// surfaces are cut out the same way in both modes.
enum class BlendRays : uint8_t {
  kStochastic,  ///< pass through with probability 1 - alpha (hash of ray and triangle)
  kHit,         ///< report them as hits: the integrator blends (Whitted)
};

struct Ray {
  Vec3 o, d;  ///< origin and direction (direction need not be unit length)
  float tmin = 0.0f;
  float tmax = kInfinity;
  BlendRays blend = BlendRays::kStochastic;
  /// When in the shutter the ray travels, 0 (open) to 1 (close), as Embree's RTCRay::time:
  /// moving primitives are placed at this time (core/motion.h). A path keeps its camera ray's.
  float time = 0.0f;
};

/// Writes into `r` a ray leaving surface point p (geometric normal ng) in direction d, offset
/// to the side d goes, at shutter time `time` (the path's: SurfacePoint::time). Field by field
/// into an existing ray: assigning `r = Ray{...}` makes the compiler build the ray in a
/// temporary with narrow stores and copy it with 16-byte loads, which cannot be forwarded from
/// those stores: a store-forwarding stall per ray, which perf showed as about 15% of the path
/// tracer's per-vertex step (docs/wavefront.md).
inline void setSpawnRay(Ray& r, const Vec3& p, const Vec3& ng, const Vec3& d, float time) {
  r.o = spawnOrigin(p, ng, d);
  r.d = d;
  r.tmin = 0.0f;
  r.tmax = kInfinity;
  r.blend = BlendRays::kStochastic;
  r.time = time;
}
/// A shadow ray from p towards target, stopping just before the target point, at `time`.
inline void setSpawnRayTo(Ray& r, const Vec3& p, const Vec3& ng, const Vec3& target, float time) {
  r.o = spawnOrigin(p, ng, target - p);
  r.d = target - r.o;
  r.tmin = 0.0f;
  r.tmax = 1.0f - 1e-4f;
  r.blend = BlendRays::kStochastic;
  r.time = time;
}

/// The same rays as new values.
inline Ray spawnRay(const Vec3& p, const Vec3& ng, const Vec3& d, float time) {
  Ray r;
  setSpawnRay(r, p, ng, d, time);
  return r;
}
inline Ray spawnRayTo(const Vec3& p, const Vec3& ng, const Vec3& target, float time) {
  Ray r;
  setSpawnRayTo(r, p, ng, target, time);
  return r;
}

}  // namespace tray
