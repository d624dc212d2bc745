#pragma once
// An environment light from an equirectangular radiance map, importance-sampled (pbrt-v4
// 12.5.3 ImageInfiniteLight, with the lat-long parameterisation of pbrt-v3 14.2.4).
//
// Direction <-> (u, v), Mitsuba 3's `envmap` convention (+Y up), in the map's own frame:
//   u = atan2(d.x, -d.z) / (2 pi) wrapped to [0,1),  v = acos(d.y) / pi
//   d = (sin(phi) sin(theta), cos(theta), -cos(phi) sin(theta)),  phi = 2 pi u, theta = pi v
// so v = 0 (row 0, the image's top) is +Y, u = 0 (the left edge) faces -Z, u = 0.25 faces +X,
// and u = 0.5 (the image's centre column) faces +Z. `rotation` turns the map by that many
// degrees about +Y (right-handed: +X goes towards -Z), like Mitsuba's
// to_world = rotate([0, 1, 0], angle). Texels are placed as Mitsuba 3 places them: column i at
// u = (i + 0.5) / W (wrapping across the seam), row j at v = j / (H - 1) (the first and last
// rows lie on the poles); Le interpolates bilinearly between them. Importance sampling uses
// cells u in [i, i+1) / W, v in [j, j+1) / H.
#include <memory>

#include "core/light.h"
#include "core/light_desc.h"
#include "lights/piecewise_constant.h"

namespace tray {

class ImageEnvironmentLight final : public Light {
 public:
  /// `map` must be non-empty with finite values >= 0; rotation in degrees, intensity >= 0.
  /// `uniform`: sample directions uniformly over the sphere (the baseline benches compare).
  ImageEnvironmentLight(std::shared_ptr<const EnvironmentMap> map, float rotationDegrees,
                        float intensity, float sceneRadius, bool uniform = false);

  uint8_t flags() const override { return kLightInfinite; }
  /// pbrt's Phi: 4 pi (pi R^2) x the map's mean luminance over the sphere (so a constant map
  /// has the power of the constant environment of the same radiance).
  float power() const override { return power_; }
  /// Ambient: pi x the map's mean luminance over the sphere.
  LightBounds bounds() const override;
  LightSample sample(const LightSampleContext& ctx, Vec2 u) const override;
  float pdf(const LightSampleContext& ctx, const Vec3& wi, const Vec3& p,
            const Vec3& n) const override;
  Color Le(const Vec3& dir) const override;
  /// Directions from the map's distribution (as sample()); origins on the world's disk.
  LightLeSample sampleLe(Vec2 u1, Vec2 u2, const WorldSphere& world) const override;
  LightLePdf pdfLe(const Vec3& p, const Vec3& n, const Vec3& w,
                   const WorldSphere& world) const override;


  /// The map's (u, v) of a world direction, and back (unit directions; the convention above).
  Vec2 directionToUv(const Vec3& worldDir) const;
  Vec3 uvToDirection(Vec2 uv) const;
  /// The map's radiance at (u, v), bilinear, times the intensity.
  Color lookup(Vec2 uv) const;

 private:
  std::shared_ptr<const EnvironmentMap> map_;
  float cosRot_ = 1, sinRot_ = 0;  ///< world = R_y(rotation) * map
  float intensity_ = 1;
  float power_ = 0;
  float meanLuminance_ = 0;  ///< over the sphere, times the intensity
  PiecewiseConstant2D distribution_;
};

}  // namespace tray
