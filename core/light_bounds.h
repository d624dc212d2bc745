#pragma once
// What a light chooser may know about a light without sampling it: where it is, which way it
// emits and how strongly, so that it can estimate the light's contribution at a shading point
// (Conty Estevez & Kulla 2018, "Importance Sampling of Many Lights with Adaptive Tree
// Splitting", sec. 4; pbrt-v4 12.6.3's LightBounds). Lights return one (core/light.h);
// lights/bvh_light_sampler.h builds a tree of them.
#include <algorithm>
#include <cmath>

#include "core/bounds.h"
#include "core/light.h"

namespace tray {

struct LightBounds {
  enum class Kind : uint8_t {
    kFinite,       ///< a box of emitters with a cone of emission directions
    kDirectional,  ///< a sun: irradiance phi along the unit direction w (towards the light)
    kAmbient,      ///< an environment: phi = pi x its mean radiance (a hemisphere's irradiance)
  };
  Kind kind = Kind::kFinite;
  Bounds3 box;         ///< kFinite: the emitting points
  Vec3 w{0, 0, 1};     ///< kFinite: the cone's axis (emission normals); kDirectional: to light
  /// Estimated strength in irradiance units once divided by d^2 (kFinite: the largest radiant
  /// intensity, e.g. luminance(Le) x area for a flat emitter), or the irradiance itself.
  float phi = 0;
  float cosTheta_o = 1;  ///< kFinite: normals lie within theta_o of w
  float sinTheta_o = 0;  ///< its sine, kept: importance() runs twice per level of the tree
  float cosTheta_e = 0;  ///< kFinite: each normal emits within theta_e of itself
  bool twoSided = false;  ///< kFinite: emits along -w's cone too

  static LightBounds finite(const Bounds3& box, const Vec3& w, float phi, float cosTheta_o,
                            float cosTheta_e, bool twoSided) {
    const float sinTheta_o = std::sqrt(std::max(0.0f, 1.0f - cosTheta_o * cosTheta_o));
    return {Kind::kFinite, box, w, phi, cosTheta_o, sinTheta_o, cosTheta_e, twoSided};
  }
  static LightBounds directional(const Vec3& towardsLight, float irradiance) {
    LightBounds b;
    b.kind = Kind::kDirectional;
    b.w = towardsLight;
    b.phi = irradiance;
    return b;
  }
  static LightBounds ambient(float meanRadiance) {
    LightBounds b;
    b.kind = Kind::kAmbient;
    b.phi = kPi * meanRadiance;
    return b;
  }

  /// An estimate of the light's contribution at ctx (irradiance units), and never 0 where the
  /// light can contribute: the chooser gives a light of importance 0 probability 0. Kinds:
  /// kFinite: phi cos(theta') cos(theta_i') / d^2, where theta' and theta_i' are the smallest
  ///   angles, over the box as seen from ctx.p, between emission and the cone and between
  ///   the receiver's normal and the light (Conty Estevez & Kulla, eq. 3), and d the distance
  ///   to the box's centre, at least half its bounding radius r (Cycles; inside the box:
  ///   phi / r^2); 0 when no point of the box can emit towards ctx.p or lies above the
  ///   receiver's horizon.
  /// kDirectional: phi cos(theta_i); kAmbient: phi.
  /// The receiver's horizon culls only when !ctx.belowMatters.
  float importance(const LightSampleContext& ctx) const;
};

/// The bounds of two lights together (Conty Estevez & Kulla sec. 4.1: the union of the boxes
/// and the smallest cone holding both cones). Both kFinite; a bound with phi 0 is ignored.
LightBounds unite(const LightBounds& a, const LightBounds& b);

}  // namespace tray
