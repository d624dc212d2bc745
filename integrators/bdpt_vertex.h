#pragma once
// The vertices of bidirectional path tracing's subpaths (Veach 1997 §10.2; the structure of
// pbrt-v3 16.3's Vertex): where each one is, what it carries, and the densities with which
// either subpath would generate it, in area measure (solid angle for vertices at infinity).
#include <cmath>
#include <cstdint>

#include "core/hit.h"
#include "core/material.h"
#include "core/math.h"
#include "materials/bsdf.h"

namespace tray {

struct BdptVertex {
  enum class Kind : uint8_t {
    kCamera,       ///< z0: the pinhole
    kLight,        ///< y0: a point on a light, or a direction from a light at infinity
    kSurface,      ///< a scattering (or emitting, or unlit) surface point
    kEnvironment,  ///< a camera subpath that escaped: the infinite lights in direction `dir`
  };
  Kind kind = Kind::kSurface;
  Vec3 p;      ///< position (unused at infinity)
  Vec3 ng;     ///< geometric normal (surfaces, area lights); zero: no cosine (points, camera)
  Vec3 n;      ///< surface: shading normal on the side the subpath arrived from
  Vec3 wo;     ///< surface: unit direction toward the previous vertex of its subpath
  Vec3 dir;    ///< at infinity: the unit direction light travels (into the scene)
  Color beta;  ///< the subpath's throughput up to and including this vertex
  /// Density of this vertex as its own subpath generated it, and as the other subpath would
  /// (from the vertex after it in this subpath's order); 0 for delta choices (remapped to 1).
  float pdfFwd = 0, pdfRev = 0;
  bool delta = false;       ///< sampled by a delta lobe (surfaces)
  bool deltaLight = false;  ///< a light vertex of a point, spot or directional light
  bool infinite = false;    ///< at infinity (environment, directional light): `dir` only
  int light = -1;           ///< light vertex: its LightSet index; surface: the light it is, or -1
  // Surface vertices only:
  SurfacePoint s;
  ShadingMaterial sm;
  const Material* m = nullptr;
  float eta = 1;            ///< n_t / n_i across the surface for light arriving from n's side
  bool refractive = false;  ///< a transmissive surface whose crossing changes the medium
  bool unlit = false;       ///< KHR_materials_unlit: emits baseColor, scatters nothing
  bool nonDelta = false;    ///< the BSDF has a lobe that is not a delta (Bsdf::hasNonDelta)
  Color sigmaA{0.0f};       ///< absorption of the medium on n's side
  Color sigmaFar{0.0f};     ///< absorption beyond the surface (refractive ones)
  Color Le{0.0f};           ///< surface: radiance it emits toward wo

  bool onSurface() const { return kind == Kind::kSurface; }
  /// The normal of the emitting face: an emitter hit's front face, a light vertex's normal.
  Vec3 emitNormal() const { return onSurface() ? s.front : ng; }
  /// A connection can end here: a point with a BSDF that is not all deltas, or a light, or the
  /// camera.
  bool connectible() const { return kind != Kind::kSurface || (!unlit && nonDelta); }
  /// The BSDF here with its normal toward wo's side (the side the subpath arrived from).
  Bsdf bsdf() const { return Bsdf(sm, n, eta); }
  /// The same BSDF with its normal toward w's side: evaluated or sampled with w as the
  /// outgoing direction (materials/bsdf.h: n faces wo).
  Bsdf bsdfFacing(const Vec3& w) const {
    return dot(w, n) >= 0 ? Bsdf(sm, n, eta) : Bsdf(sm, -n, 1.0f / eta);
  }
  /// Absorption along a segment leaving this surface in direction w: the medium on w's side.
  Color absorptionToward(const Vec3& w) const {
    return refractive && dot(w, n) < 0 ? sigmaFar : sigmaA;
  }
};

/// A solid-angle density at `from` of the direction toward `to`, as an area density at `to`
/// (Veach 1997 §8.2.2: dA = d^2 dω / |cos θ|): unchanged for a vertex at infinity; no cosine
/// for a point without a surface.
/// The unit direction from a toward b (either may be at infinity).
inline Vec3 directionTo(const BdptVertex& a, const BdptVertex& b) {
  if (b.infinite) return -b.dir;
  if (a.infinite) return a.dir;
  return normalize(b.p - a.p);
}

inline float toArea(float pdfDir, const BdptVertex& from, const BdptVertex& to) {
  if (to.infinite) return pdfDir;
  const Vec3 d = to.p - from.p;
  const float d2 = dot(d, d);
  if (!(d2 > 0)) return 0.0f;
  float pdf = pdfDir / d2;
  if (to.ng != Vec3(0.0f)) pdf *= std::fabs(dot(to.ng, d)) / std::sqrt(d2);
  return pdf;
}

/// The shading-normal correction of adjoint transport (Veach 1997 §5.3): importance leaving a
/// surface along wi, having arrived along wo (both away from it), is scaled by
/// |wo·ns| |wi·ng| / (|wo·ng| |wi·ns|), so that f* stays the adjoint with shading normals.
inline float shadingCorrection(const BdptVertex& v, const Vec3& wo, const Vec3& wi) {
  const float den = std::fabs(dot(wo, v.s.ng)) * std::fabs(dot(wi, v.n));
  if (!(den > 0)) return 0.0f;
  return std::fabs(dot(wo, v.n)) * std::fabs(dot(wi, v.s.ng)) / den;
}

}  // namespace tray
