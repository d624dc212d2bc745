#pragma once
// What an estimator decides at a surface vertex before it shades it, shared by path
// (integrators/path_estimator.cpp) and bdpt (integrators/bdpt_tracer.cpp, bdpt_connect.cpp).
#include "core/integrator.h"
#include "core/material.h"
#include "core/math.h"

namespace tray {

/// False interfaces of nested dielectrics a path passes through before it is given up.
inline constexpr int kMaxNullCrossings = 64;

/// Light crossing the surface changes the medium (nested dielectrics, MediumStack): it
/// transmits, and is not all metal. A metallicRoughnessTexture can lower metallic below a
/// factor of 1 (glTF's default factor, which the Khronos transmission samples keep): such a
/// surface may transmit too.
inline bool isRefractive(const Material& m) {
  return m.transmission > 0 && (m.metallic < 1 || m.metallicRoughnessTexture.valid());
}

/// The clearcoat and sheen are on the outside of a transmissive solid: not seen from within.
inline void hideOuterLayersInside(ShadingMaterial& sm, bool refractive, bool frontFace) {
  if (refractive && !frontFace) sm.clearcoat = 0, sm.sheenColor = Color(0.0f);
}

/// LightSampleContext::belowMatters: a reflecting BSDF sees only light above n unless wo lies
/// below it (shading normals) or a clearcoat brings a normal of its own.
inline bool belowMatters(bool transmits, const Vec3& wo, const Vec3& n, const ShadingMaterial& sm) {
  return transmits || !(dot(wo, n) > 0) || sm.clearcoat > 0;
}

/// The first surface a camera ray met, for the AOVs and Cryptomatte: `cameraOrigin` the ray's
/// origin (depth), `shadingN` and `albedo` as shaded there.
inline void recordPrimaryHit(PrimaryHit& primary, const Scene& scene, const SurfacePoint& s,
                             const Vec3& cameraOrigin, const Vec3& shadingN, const Color& albedo) {
  primary.hit = true;
  primary.depth = length(s.p - cameraOrigin);
  primary.position = s.p;
  primary.primitive = s.primitive, primary.instance = s.instance, primary.time = s.time;
  primary.normal = shadingN;
  primary.albedo = albedo;
  primary.objectId = scene.objectId(s.primitive, s.instance);
  primary.materialId = s.material;
}

}  // namespace tray
