#pragma once
// The light interface (pbrt-v4 12.1: Light::SampleLi / PDF_Li / Phi / Le). Implementations live
// in lights/; integrators see only this interface and the LightSet that chooses among lights.
#include <cstdint>

#include "core/math.h"

namespace tray {

/// The receiving point a light is sampled from (pbrt-v4's LightSampleContext).
struct LightSampleContext {
  Vec3 p;                  ///< the reference point
  Vec3 n;                  ///< its shading normal, on the side being shaded
  bool transmits = false;  ///< the receiver also scatters below n (directions there matter)
  /// Light from below n may reach the receiver's BSDF: it transmits, or the outgoing direction
  /// lies below n (shading normals), or a lobe has a normal of its own (a clearcoat's). Light
  /// choosers may neglect lights wholly below n only when this is false.
  bool belowMatters = false;
};

struct LightBounds;  // core/light_bounds.h

/// A direction towards a light from a reference point, with what arrives along it.
struct LightSample {
  Color L;                ///< radiance arriving (delta lights: intensity / d^2 or irradiance)
  Vec3 wi;                ///< unit direction from the reference point towards the light
  Vec3 p;                 ///< the point on the light (finite lights) for the shadow ray
  float pdf = 0;          ///< solid-angle density of wi (1 for delta lights); 0 = no sample
  bool delta = false;     ///< point, spot, directional: MIS does not apply
  bool infinite = false;  ///< directional, environment: the shadow ray is unbounded
  bool valid() const { return pdf > 0; }
};

/// What kind of light, as pbrt-v4's LightType: delta lights are reached only by light
/// sampling; infinite lights are seen by rays that escape the scene (Le).
enum LightFlags : uint8_t {
  kLightArea = 1,            ///< emission from a surface; found by BSDF sampling too
  kLightDeltaPosition = 2,   ///< point, spot
  kLightDeltaDirection = 4,  ///< directional
  kLightInfinite = 8,        ///< environment: radiance from every escaping direction
};

class Light {
 public:
  virtual ~Light() = default;
  virtual uint8_t flags() const = 0;
  bool isDelta() const { return flags() & (kLightDeltaPosition | kLightDeltaDirection); }
  /// Total emitted power (any consistent estimate; luminance): the light chooser picks lights
  /// in proportion to it.
  virtual float power() const = 0;
  /// Where the light is and how it emits, for choosers that weigh lights by their estimated
  /// contribution at the shading point (core/light_bounds.h).
  virtual LightBounds bounds() const = 0;
  /// A direction towards the light from ctx, with u uniform in [0,1)^2. pdf is per solid angle
  /// (1 for delta lights); an invalid sample (pdf 0) when the light cannot reach ctx.p.
  virtual LightSample sample(const LightSampleContext& ctx, Vec2 u) const = 0;
  /// The solid-angle pdf with which sample() from ctx returns direction wi. Finite lights get
  /// the point p where wi meets them and the geometric normal n there (the caller found them
  /// by tracing wi, so the light need not intersect again); 0 for delta lights.
  virtual float pdf(const LightSampleContext& ctx, const Vec3& wi, const Vec3& p,
                    const Vec3& n) const = 0;
  /// Radiance arriving along a ray that escaped the scene in direction dir (infinite lights).
  virtual Color Le(const Vec3& dir) const {
    (void)dir;
    return Color(0.0f);
  }
};

}  // namespace tray
