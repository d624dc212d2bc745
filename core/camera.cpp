#include "core/camera.h"

#include "core/camera_lanes.h"
#include "core/error.h"
#include "core/sampling.h"

namespace tray {
namespace {

/// A camera-space ray from o along d (d.z < 0) in world space, starting at view depth znear.
Ray lensRay(const Transform& toWorld, const Vec3& o, const Vec3& d, float znear) {
  Ray r;
  r.o = toWorld.point(o);
  const Vec3 w = toWorld.vector(d);
  r.d = normalize(w);
  r.tmin = znear * length(w) / -d.z;
  return r;
}

/// The thin lens both projections share (pbrt-v4 4th ed. §5.2.3): the ray from the aperture
/// point that u picks meets the pinhole ray of the same raster position (from `pinholeOrigin`
/// along `pinholeDir`, camera space, z = -1) in the plane in focus, so that plane is imaged
/// sharply and other depths blur into the aperture's shape.
struct ThinLens {
  float radius = 0, focus = 0;
  int blades = 0;
  explicit ThinLens(const CameraDesc& d)
      : radius(d.lensRadius), focus(d.focusDistance), blades(d.apertureBlades) {}
  Ray ray(const Transform& toWorld, const Vec3& pinholeOrigin, const Vec3& pinholeDir,
          const Vec2& u, float znear) const {
    const Vec2 a = sampleAperture(u, blades);
    const Vec3 o = pinholeOrigin + Vec3(radius * a.x, radius * a.y, 0.0f);
    return lensRay(toWorld, o, pinholeOrigin + focus * pinholeDir - o, znear);
  }
};

class PerspectiveCamera final : public Camera {
 public:
  PerspectiveCamera(const CameraDesc& d, int w, int h)
      : toWorld_(d.toWorld), w_(float(w)), h_(float(h)), znear_(d.znear), lens_(d) {
    tanHalfY_ = std::tan(0.5f * d.yfov);
    // glTF: the image's aspect ratio wins over the camera's when they differ (spec 3.10.2:
    // aspectRatio is a hint); the vertical fov is kept.
    tanHalfX_ = tanHalfY_ * w_ / h_;
  }
  Ray generateRay(float x, float y) const override {
    // core/camera_lanes.h: the SIMD camera kernel's text too.
    Ray r;
    r.o = toWorld_.point(Vec3(0.0f));
    pinholeRay(toWorld_.m.m, perspectiveDirection(x, y, w_, h_, tanHalfX_, tanHalfY_), znear_, r.d,
               r.tmin);
    return r;
  }
  bool hasLens() const override { return lens_.radius > 0; }
  std::optional<PinholeProjection> pinhole() const override {
    if (hasLens()) return std::nullopt;
    return PinholeProjection{toWorld_, w_, h_, znear_, tanHalfX_, tanHalfY_};
  }
  Ray generateLensRay(float x, float y, const Vec2& u) const override {
    if (!hasLens()) return generateRay(x, y);
    const Vec3 dirCam = perspectiveDirection(x, y, w_, h_, tanHalfX_, tanHalfY_);
    return lens_.ray(toWorld_, Vec3(0.0f), dirCam, u, znear_);
  }
  void pixelSpread(const Vec3& p, Vec3& dx, Vec3& dy, Vec3& dir) const override {
    // In camera space a raster step moves a ray's point at view depth z by 2 tan(fov/2) z / size.
    Vec3 pc = toWorld_.inversePoint(p);
    float depth = std::max(std::fabs(pc.z), 1e-6f);
    dx = toWorld_.vector({2.0f * tanHalfX_ * depth / w_, 0.0f, 0.0f});
    dy = toWorld_.vector({0.0f, -2.0f * tanHalfY_ * depth / h_, 0.0f});
    Vec3 d = p - toWorld_.point(Vec3(0.0f));
    float len = length(d);
    dir = len > 0 ? d / len : normalize(toWorld_.vector({0, 0, -1}));
  }

 private:
  Transform toWorld_;
  float w_, h_, znear_, tanHalfX_, tanHalfY_;
  ThinLens lens_;
};

class OrthographicCamera final : public Camera {
 public:
  OrthographicCamera(const CameraDesc& d, int w, int h)
      : toWorld_(d.toWorld), w_(float(w)), h_(float(h)), ymag_(d.ymag), znear_(d.znear), lens_(d) {
    xmag_ = d.ymag * w_ / h_;
  }
  Ray generateRay(float x, float y) const override {
    Vec3 oCam{(2.0f * x / w_ - 1.0f) * xmag_, (1.0f - 2.0f * y / h_) * ymag_, 0.0f};
    Ray r;
    r.o = toWorld_.point(oCam);
    r.d = normalize(toWorld_.vector({0, 0, -1}));
    r.tmin = znear_ * length(toWorld_.vector({0, 0, -1}));
    return r;
  }
  bool hasLens() const override { return lens_.radius > 0; }
  Ray generateLensRay(float x, float y, const Vec2& u) const override {
    if (!hasLens()) return generateRay(x, y);
    const Vec3 oCam{(2.0f * x / w_ - 1.0f) * xmag_, (1.0f - 2.0f * y / h_) * ymag_, 0.0f};
    return lens_.ray(toWorld_, oCam, {0.0f, 0.0f, -1.0f}, u, znear_);
  }
  void pixelSpread(const Vec3&, Vec3& dx, Vec3& dy, Vec3& dir) const override {
    dx = toWorld_.vector({2.0f * xmag_ / w_, 0.0f, 0.0f});
    dy = toWorld_.vector({0.0f, -2.0f * ymag_ / h_, 0.0f});
    dir = normalize(toWorld_.vector({0, 0, -1}));
  }

 private:
  Transform toWorld_;
  float w_, h_, xmag_, ymag_, znear_;
  ThinLens lens_;
};

}  // namespace

Vec2 sampleAperture(const Vec2& u, int blades) {
  if (blades < 3) return sampleUniformDiskConcentric(u);
  // u.x picks one of the polygon's equal triangles (centre, vertex k, vertex k + 1) and its
  // fraction v a distance s = sqrt(v) towards the rim (area grows as s^2: uniform), u.y the
  // point along the scaled edge.
  const float scaled = u.x * float(blades);
  const int k = std::min(int(scaled), blades - 1);
  const float s = std::sqrt(std::max(0.0f, scaled - float(k)));
  const float step = 2.0f * kPi / float(blades), a0 = 0.5f * kPi + step * float(k);
  const float a1 = a0 + step;
  return {s * ((1.0f - u.y) * std::cos(a0) + u.y * std::cos(a1)),
          s * ((1.0f - u.y) * std::sin(a0) + u.y * std::sin(a1))};
}

std::unique_ptr<Camera> Camera::create(const CameraDesc& d, int w, int h) {
  if (w <= 0 || h <= 0) throw Error("image size must be positive");
  if (d.lensRadius > 0 && !(d.focusDistance > 0))
    throw Error("a thin-lens camera needs a focus distance > 0 (--focus-distance or "
                "TRAY_camera focusDistance)");
  std::unique_ptr<Camera> camera;
  if (d.type == CameraDesc::Type::kOrthographic)
    camera = std::make_unique<OrthographicCamera>(d, w, h);
  else
    camera = std::make_unique<PerspectiveCamera>(d, w, h);
  camera->desc_ = d;
  return camera;
}

CameraDesc Camera::framing(const Bounds3& b, float aspectRatio) {
  CameraDesc d;
  d.name = "default";
  d.yfov = 0.6f;
  d.aspectRatio = aspectRatio;
  Vec3 c = b.empty() || !b.finite() ? Vec3(0.0f) : b.center();
  float radius = b.empty() || !b.finite() ? 1.0f : 0.5f * length(b.diagonal());
  radius = std::max(radius, 1e-6f);
  // Step back along +Z (and a little up) until the bounding sphere fits the narrower fov.
  float halfFov = 0.5f * d.yfov * std::min(1.0f, aspectRatio > 0 ? aspectRatio : 1.0f);
  float dist = radius / std::sin(halfFov);
  Vec3 dir = normalize(Vec3(0.0f, 0.35f, 1.0f));
  Vec3 eye = c + dist * dir;
  Vec3 back = dir, right = normalize(cross(Vec3(0, 1, 0), back)), up = cross(back, right);
  Mat4 m;
  for (int i = 0; i < 3; ++i) {
    m.m[i][0] = right[i];
    m.m[i][1] = up[i];
    m.m[i][2] = back[i];
    m.m[i][3] = eye[i];
  }
  d.toWorld = Transform(m);
  return d;
}

}  // namespace tray
