#include "core/camera.h"

#include "core/error.h"

namespace tray {
namespace {

class PerspectiveCamera final : public Camera {
 public:
  PerspectiveCamera(const CameraDesc& d, int w, int h)
      : toWorld_(d.toWorld), w_(float(w)), h_(float(h)), znear_(d.znear) {
    tanHalfY_ = std::tan(0.5f * d.yfov);
    // glTF: the image's aspect ratio wins over the camera's when they differ (spec 3.10.2:
    // aspectRatio is a hint); the vertical fov is kept.
    tanHalfX_ = tanHalfY_ * w_ / h_;
  }
  Ray generateRay(float x, float y) const override {
    Vec3 dirCam{(2.0f * x / w_ - 1.0f) * tanHalfX_, (1.0f - 2.0f * y / h_) * tanHalfY_, -1.0f};
    Ray r;
    r.o = toWorld_.point(Vec3(0.0f));
    r.d = normalize(toWorld_.vector(dirCam));
    // The point at view depth znear is znear * dirCam (dirCam.z = -1) in camera space.
    r.tmin = znear_ * length(toWorld_.vector(dirCam));
    return r;
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
};

class OrthographicCamera final : public Camera {
 public:
  OrthographicCamera(const CameraDesc& d, int w, int h)
      : toWorld_(d.toWorld), w_(float(w)), h_(float(h)), ymag_(d.ymag), znear_(d.znear) {
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
  void pixelSpread(const Vec3&, Vec3& dx, Vec3& dy, Vec3& dir) const override {
    dx = toWorld_.vector({2.0f * xmag_ / w_, 0.0f, 0.0f});
    dy = toWorld_.vector({0.0f, -2.0f * ymag_ / h_, 0.0f});
    dir = normalize(toWorld_.vector({0, 0, -1}));
  }

 private:
  Transform toWorld_;
  float w_, h_, xmag_, ymag_, znear_;
};

}  // namespace

std::unique_ptr<Camera> Camera::create(const CameraDesc& d, int w, int h) {
  if (w <= 0 || h <= 0) throw Error("image size must be positive");
  if (d.type == CameraDesc::Type::kOrthographic)
    return std::make_unique<OrthographicCamera>(d, w, h);
  return std::make_unique<PerspectiveCamera>(d, w, h);
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
