#pragma once
#include "core/front_face.h"
#include "core/light.h"
#include "core/sampling.h"
#include "core/shape.h"
// sampleTriangle and sampleRectangle, written once for scalar code and the SIMD stages.
#include "lights/rectangle_light_lanes.h"
#include "lights/triangle_light_lanes.h"
#include "lights/triangle_sampling.h"

namespace tray {

/// A diffuse area light (pbrt-v4 12.5.1's DiffuseAreaLight): constant radiance Le leaving the
/// front face of an emitter (both faces when doubleSided; core/front_face.h owns the rule),
/// over one emissive mesh triangle, a rectangle that two mesh triangles form
/// (lights/quad_lights.h) or any analytic shape that can be sampled
/// (Shape::area > 0). Triangles and rectangles are sampled uniformly by area or by solid angle, per
/// receiver as TriangleSampling says (kept inline: meshes bring many); shapes through
/// Shape::sample(ctx, u), e.g. a sphere's cone of directions.
class AreaLight final : public Light {
 public:
  /// One triangle in world space; `front` is its front-face normal (triangleFrontNormal).
  static AreaLight triangle(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& front,
                            const Color& Le, bool doubleSided,
                            TriangleSampling sampling = TriangleSampling::kAuto);
  /// The rectangle corner + s ex + t ey (s, t in [0, 1]) in world space; ex and ey are
  /// perpendicular (lights/quad_lights.h makes them so), `front` its front-face normal.
  static AreaLight rectangle(const Vec3& corner, const Vec3& ex, const Vec3& ey, const Vec3& front,
                             const Color& Le, bool doubleSided, TriangleSampling sampling);
  /// An analytic shape placed by toWorld. Both are referenced, not copied: they must outlive
  /// the light (they belong to the Scene).
  static AreaLight shape(const Shape& shape, const Transform& toWorld, const Color& Le,
                         bool doubleSided);

  uint8_t flags() const override { return kLightArea; }
  /// Le x area x pi per emitting face. A closed shape's inside never lights the scene, so a
  /// shape counts one face even when doubleSided; a two-sided triangle counts two.
  float power() const override;
  /// A triangle: its box and normal cone (theta_o 0, theta_e pi/2), phi = luminance(Le) x
  /// area, its largest radiant intensity. A shape: its world box, all directions, phi =
  /// luminance(Le) x area / 4 (a convex body's mean projected area is a quarter of its area).
  LightBounds bounds() const override;
  /// Inline, and LightSet calls it through the final class: a triangle is then sampled with
  /// no call at all (callgrind, Cornell box: AreaLight::sample's own ~15 instructions and the
  /// calls gone).
  LightSample sample(const LightSampleContext& ctx, Vec2 u) const override {
    return shape_       ? sampleShape(ctx, u)
           : rectangle_ ? sampleRectangle(ctx.p, ctx.n, u)
                        : sampleTriangle(ctx.p, ctx.n, u);
  }
  float pdf(const LightSampleContext& ctx, const Vec3& wi, const Vec3& p,
            const Vec3& n) const override {
    if (shape_) return shapePdf(ctx, wi, p, n);
    const Vec3 d = p - ctx.p;
    const float dist2 = lengthSquared(d), dist = std::sqrt(dist2);
    if (rectangle_)
      return rectangleLightPdf(triangleLight(), ctx.p, ctx.n, d, dist2, dot(n_, d) / dist,
                               sampling_);
    return triangleLightPdf(triangleLight(), ctx.p, ctx.n, d / dist, dist2, dot(n_, d) / dist,
                            sampling_);
  }
  /// Uniform over the area (a shape's sampleArea is uniform too), cosine-weighted about the
  /// emitting face's normal (either face, each with probability 1/2, for a two-sided triangle;
  /// a shape emits outward only, as power() counts).
  LightLeSample sampleLe(Vec2 u1, Vec2 u2, const WorldSphere& world) const override;
  LightLePdf pdfLe(const Vec3& p, const Vec3& n, const Vec3& w,
                   const WorldSphere& world) const override;
  float area() const { return area_; }
  /// A triangle's world-space data, as sampleTriangle reads it (the SIMD matte stage,
  /// integrators/matte_batch.h, copies it into its table). Only when isTriangle().
  bool isTriangle() const { return shape_ == nullptr && !rectangle_; }
  /// A rectangle (AreaLight::rectangle): p0, e1, e2 of triangleData are its corner and edges.
  bool isRectangle() const { return rectangle_; }
  struct Triangle {
    Vec3 p0, e1, e2, n;
    float area;
    Color Le;
    bool doubleSided;
  };
  Triangle triangleData() const { return {p0_, e1_, e2_, n_, area_, Le_, doubleSided_}; }
  /// How a triangle is sampled (the SIMD stages read it from their tables).
  TriangleSampling triangleSampling() const { return sampling_; }

 private:
  AreaLight() = default;
  LightSample sampleTriangle(const Vec3& ref, const Vec3& n, Vec2 u) const {
    return emitted(sampleTriangleLight(triangleLight(), ref, n, u, sampling_));
  }
  LightSample sampleRectangle(const Vec3& ref, const Vec3& n, Vec2 u) const {
    return emitted(sampleRectangleLight(triangleLight(), ref, n, u, sampling_));
  }
  /// A triangle's or rectangle's point as a LightSample carrying this light's radiance.
  LightSample emitted(const TriangleLightSampleOf<Vec3>& t) const {
    LightSample s;
    if (!t.valid) return s;
    s.p = t.p, s.wi = t.wi, s.pdf = t.pdf;
    s.L = Le_;
    return s;
  }
  LightSample sampleShape(const LightSampleContext& ctx, Vec2 u) const;
  float shapePdf(const LightSampleContext& ctx, const Vec3& wi, const Vec3& p, const Vec3& n) const;
  TriangleLightOf<Vec3> triangleLight() const { return {p0_, e1_, e2_, n_, area_, doubleSided_}; }

  const Shape* shape_ = nullptr;  ///< null: a triangle
  const Transform* toWorld_ = nullptr;
  Vec3 p0_, e1_, e2_;  ///< triangle: vertex 0 and the edges to vertices 1 and 2 (world)
  Vec3 n_;             ///< triangle: unit front-face normal
  float area_ = 0;     ///< world area
  Color Le_;
  bool doubleSided_ = false;
  bool rectangle_ = false;  ///< p0_, e1_, e2_: a rectangle's corner and edges
  TriangleSampling sampling_ = TriangleSampling::kAuto;  ///< triangle: by area or solid angle
};

}  // namespace tray
