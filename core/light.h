#pragma once
// The light interface (pbrt-v4 12.1: Light::SampleLi / PDF_Li / Phi / Le). Implementations live
// in lights/; integrators see only this interface and the LightSet that chooses among lights.
#include <cstdint>

#include "core/math.h"
#include "core/ray.h"

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

/// The sphere that bounds the scene: infinite lights (the environment, a directional light)
/// emit from a disk of its radius facing the scene (pbrt-v4 12.4 and 12.5, SampleLe).
struct WorldSphere {
  Vec3 center{0.0f};
  float radius = 1.0f;
};

/// A ray leaving a light, for estimators that trace paths from the lights (photon mapping,
/// bidirectional path tracing): pbrt-v4's LightLeSample. The ray's weight is
/// L |cos| / (pdfPos pdfDir), the cosine taken at the light's surface (area lights only; 1
/// for the others).
struct LightLeSample {
  Ray ray;  ///< leaving the light: the origin on it, a unit direction
  /// Radiance along the ray (area lights, environment); radiant intensity (point, spot);
  /// irradiance (directional).
  Color L;
  Vec3 n;  ///< the light's surface normal at ray.o, on the emitting side; zero for the others
  /// Density of the origin: per area (area lights, per area of the disk of an infinite light);
  /// 1 for a delta position (point, spot).
  float pdfPos = 0;
  /// Density of the direction per solid angle; 1 for a delta direction (directional).
  float pdfDir = 0;
  bool valid() const { return pdfPos > 0 && pdfDir > 0 && !isBlack(L); }
};

/// The densities with which sampleLe would emit a given ray (pbrt-v4's PDF_Le); 0 where it
/// never does, and for a delta's part (a point light's position, a directional light's
/// direction).
struct LightLePdf {
  float pos = 0, dir = 0;
};

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
  /// A ray leaving the light, u1 placing its origin and u2 its direction (pbrt-v4 12's
  /// SampleLe); `world` bounds the scene, for infinite lights. Invalid (pdfs 0) when the
  /// light emits nothing.
  virtual LightLeSample sampleLe(Vec2 u1, Vec2 u2, const WorldSphere& world) const = 0;
  /// The densities of sampleLe for a ray leaving the light at p (surface normal n; area
  /// lights) in unit direction w. Infinite lights read only w (travelling into the scene).
  virtual LightLePdf pdfLe(const Vec3& p, const Vec3& n, const Vec3& w,
                           const WorldSphere& world) const = 0;
  /// Radiance arriving along a ray that escaped the scene in direction dir (infinite lights).
  virtual Color Le(const Vec3& dir) const {
    (void)dir;
    return Color(0.0f);
  }
};

}  // namespace tray
