#include "lights/image_environment_light.h"

#include <algorithm>
#include <cmath>

#include "core/light_bounds.h"

namespace tray {

namespace {

Color pixel(const EnvironmentMap& m, int x, int y) {
  const float* p = &m.rgb[(size_t(y) * size_t(m.width) + size_t(x)) * 3];
  return {p[0], p[1], p[2]};
}

/// Sampling weights over cells of u in [i, i+1) / W, v in [j, j+1) / H: luminance x
/// sin(theta), the Jacobian of the lat-long map (pbrt-v3 14.2.4). Le is bilinear between texels
/// (rows at v = j / (H - 1)), so a point in cell (i, j) can see the 3 x 3 texels around it:
/// each cell takes the largest luminance there, and wherever Le > 0 the pdf is > 0 (light
/// sampling alone is unbiased; the cost is a slightly wider distribution around a sun).
std::vector<float> samplingWeights(const EnvironmentMap& m, bool uniform) {
  const int w = m.width, h = m.height;
  std::vector<float> lum(size_t(w) * size_t(h)), f(lum.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) lum[size_t(y) * size_t(w) + size_t(x)] = luminance(pixel(m, x, y));
  for (int y = 0; y < h; ++y) {
    const float sinTheta = std::sin(kPi * (float(y) + 0.5f) / float(h));
    for (int x = 0; x < w; ++x) {
      float most = uniform ? 1.0f : 0.0f;
      for (int dy = -1; dy <= 1 && !uniform; ++dy) {
        const int yy = std::clamp(y + dy, 0, h - 1);
        for (int dx = -1; dx <= 1; ++dx) {
          const int xx = (x + dx + w) % w;
          most = std::max(most, lum[size_t(yy) * size_t(w) + size_t(xx)]);
        }
      }
      f[size_t(y) * size_t(w) + size_t(x)] = most * sinTheta;
    }
  }
  return f;
}

}  // namespace

ImageEnvironmentLight::ImageEnvironmentLight(std::shared_ptr<const EnvironmentMap> map,
                                             float rotationDegrees, float intensity,
                                             float sceneRadius, bool uniform)
    : map_(std::move(map)), intensity_(intensity) {
  const double rad = double(rotationDegrees) * 3.14159265358979323846 / 180.0;
  cosRot_ = float(std::cos(rad)), sinRot_ = float(std::sin(rad));
  const int w = map_->width, h = map_->height;
  // Mean radiance over the sphere: (1 / 4 pi) sum L sin(theta) (2 pi / W) (pi / H).
  double sum = 0;
  for (int y = 0; y < h; ++y) {
    const double sinTheta = std::sin(3.14159265358979323846 * (y + 0.5) / h);
    double row = 0;
    for (int x = 0; x < w; ++x) row += luminance(pixel(*map_, x, y));
    sum += row * sinTheta;
  }
  const double mean = sum * (2.0 * kPi / w) * (kPi / h) / (4.0 * kPi);
  meanLuminance_ = float(mean * intensity_);
  power_ = float(4.0 * kPi * kPi * double(sceneRadius) * sceneRadius * mean * intensity_);
  distribution_ = PiecewiseConstant2D(samplingWeights(*map_, uniform), size_t(w), size_t(h));
}

Vec2 ImageEnvironmentLight::directionToUv(const Vec3& d) const {
  // Into the map's frame: the inverse rotation R_y(-angle).
  const Vec3 m(cosRot_ * d.x - sinRot_ * d.z, d.y, sinRot_ * d.x + cosRot_ * d.z);
  float u = std::atan2(m.x, -m.z) * (0.5f / kPi);
  if (u < 0) u += 1.0f;
  if (u >= 1.0f) u = 0.0f;
  const float v = std::acos(std::clamp(m.y, -1.0f, 1.0f)) / kPi;
  return {u, v};
}

Vec3 ImageEnvironmentLight::uvToDirection(Vec2 uv) const {
  const float phi = 2.0f * kPi * uv.x, theta = kPi * uv.y;
  const float sinTheta = std::sin(theta);
  const Vec3 m(std::sin(phi) * sinTheta, std::cos(theta), -std::cos(phi) * sinTheta);
  // To world: R_y(angle) maps (x, z) to (c x + s z, -s x + c z).
  return {cosRot_ * m.x + sinRot_ * m.z, m.y, -sinRot_ * m.x + cosRot_ * m.z};
}

Color ImageEnvironmentLight::lookup(Vec2 uv) const {
  const int w = map_->width, h = map_->height;
  // Mitsuba 3's texel placement: columns centred at u = (i + 0.5) / W, wrapping across the
  // seam; rows from pole to pole, row j at v = j / (H - 1).
  const float x = uv.x * float(w) - 0.5f, y = uv.y * float(std::max(h - 1, 1));
  const float fx = std::floor(x), fy = std::floor(y);
  const float tx = x - fx, ty = y - fy;
  const int x0 = ((int(fx) % w) + w) % w, x1 = (x0 + 1) % w;
  const int y0 = std::clamp(int(fy), 0, h - 1), y1 = std::clamp(int(fy) + 1, 0, h - 1);
  const Color top = (1 - tx) * pixel(*map_, x0, y0) + tx * pixel(*map_, x1, y0);
  const Color bottom = (1 - tx) * pixel(*map_, x0, y1) + tx * pixel(*map_, x1, y1);
  return intensity_ * ((1 - ty) * top + ty * bottom);
}

Color ImageEnvironmentLight::Le(const Vec3& dir) const {
  return lookup(directionToUv(dir));
}

LightSample ImageEnvironmentLight::sample(const LightSampleContext&, Vec2 u) const {
  LightSample s;
  float mapPdf = 0;
  const Vec2 uv = distribution_.sample(u, mapPdf);
  const float sinTheta = std::sin(kPi * uv.y);
  // pdf over solid angle = pdf over [0,1)^2 / (2 pi^2 sin(theta)) (pbrt-v3 eq. 14.11).
  if (!(mapPdf > 0) || !(sinTheta > 0)) return s;
  s.wi = normalize(uvToDirection(uv));
  s.L = lookup(uv);
  s.pdf = mapPdf / (2.0f * kPi * kPi * sinTheta);
  s.infinite = true;
  return s;
}

float ImageEnvironmentLight::pdf(const LightSampleContext&, const Vec3& wi, const Vec3&,
                                 const Vec3&) const {
  const Vec2 uv = directionToUv(wi);
  const float sinTheta = std::sin(kPi * uv.y);
  if (!(sinTheta > 0)) return 0.0f;
  return distribution_.pdf(uv) / (2.0f * kPi * kPi * sinTheta);
}

LightBounds ImageEnvironmentLight::bounds() const { return LightBounds::ambient(meanLuminance_); }

}  // namespace tray
