#pragma once
// The AOVs that are averaged over all of a pixel's samples, as filter-weighted sums like the
// beauty's (core/pixel_sums.h): light-path radiance, albedo, normal and depth. The renderer
// passes one to Integrator::accumulate only when such layers are asked for.
#include "core/light_paths.h"
#include "core/math.h"

namespace tray {

struct AovSums {
  bool lightPaths = false;  ///< gather the light-path split (set by the renderer)
  bool surface = false;     ///< gather albedo, normal and depth (set by the renderer)
  double paths[kLightPathCount][3] = {};
  double albedo[3] = {}, normal[3] = {};
  double depth = 0;      ///< sum of w * depth over samples that hit a surface
  double hitWeight = 0;  ///< sum of w over those samples
  double weight = 0;     ///< sum of w over every sample

  /// Empties the sums, keeping what is gathered.
  void clear() {
    const bool p = lightPaths, s = surface;
    *this = AovSums();
    lightPaths = p, surface = s;
  }
  /// Every sample adds its weight here (the means' denominator, as the beauty's).
  void addWeight(double w) { weight += w; }
  void addLightPaths(const LightPathRadiance& r, double w) {
    for (int k = 0; k < kLightPathCount; ++k)
      for (int c = 0; c < 3; ++c) paths[k][c] += w * r.radiance[k][c];
  }
  /// A sample that hit nothing adds its weight only: albedo and normal average towards 0 as
  /// the background's share grows (the coverage-weighted mix a denoiser expects).
  void addSurface(bool hit, const Color& a, const Vec3& n, float d, double w) {
    if (!hit) return;
    for (int c = 0; c < 3; ++c) albedo[c] += w * a[c], normal[c] += w * n[c];
    depth += w * d;
    hitWeight += w;
  }
  /// The weighted means (0 without samples; depth +inf where no sample hit).
  Color path(int k) const { return mean(paths[k], weight); }
  Color meanAlbedo() const { return mean(albedo, weight); }
  Vec3 meanNormal() const { return mean(normal, weight); }
  float meanDepth() const { return hitWeight > 0 ? float(depth / hitWeight) : kInfinity; }

 private:
  static Color mean(const double* v, double w) {
    return w == 0 ? Color(0.0f) : Color(float(v[0] / w), float(v[1] / w), float(v[2] / w));
  }
};

}  // namespace tray
