#pragma once
#include "core/sampling.h"
#include "lights/light_sample.h"

namespace tray {

/// One emissive triangle in world space (glTF emissive x KHR_materials_emissive_strength).
/// Emits from its front face (counter-clockwise winding, i.e. along n) unless two-sided.
/// Points are sampled uniformly by area; the pdf is returned per solid angle.
struct TriangleLight {
  Vec3 p0, e1, e2;  ///< vertex 0 and the edges to vertices 1 and 2
  Vec3 n;           ///< unit front-face normal
  float area = 0;
  Color Le;
  bool twoSided = false;

  float power() const { return luminance(Le) * area * kPi * (twoSided ? 2.0f : 1.0f); }
  /// Radiance leaving the light towards -w (w: direction arriving at the light).
  Color emitted(const Vec3& w) const { return (twoSided || dot(n, w) < 0) ? Le : Color(0.0f); }
  LightSample sample(const Vec3& ref, Vec2 u) const {
    LightSample s;
    Vec3 b = sampleUniformTriangle(u);
    s.p = p0 + b.y * e1 + b.z * e2;
    Vec3 d = s.p - ref;
    float dist2 = lengthSquared(d);
    if (!(dist2 > 0)) return s;
    s.wi = d / std::sqrt(dist2);
    float cosL = -dot(n, s.wi);
    if (!twoSided && cosL <= 0) return s;
    s.pdf = pdf(dist2, cosL);
    s.L = Le;
    return s;
  }
  /// Solid-angle pdf of a point on the light at squared distance dist2 whose normal makes
  /// cosine cosL with the direction: area pdf 1/A times dA/dw = d^2 / |cos|.
  float pdf(float dist2, float cosL) const {
    float c = std::fabs(cosL);
    return c > 0 ? dist2 / (c * area) : 0.0f;
  }
};

}  // namespace tray
