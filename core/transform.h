#pragma once
#include "core/bounds.h"
#include "core/math.h"
// Points, vectors and normals placed, written once for scalar code and the SIMD kernels.
#include "core/transform_lanes.h"

namespace tray {

/// Row-major 4x4 matrix (m[row][col]); points are column vectors: p' = M p.
struct Mat4 {
  float m[4][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};
  static Mat4 identity() { return {}; }
  /// From glTF's column-major 16 floats.
  static Mat4 fromColumnMajor(const double* v);
  static Mat4 translate(const Vec3& t);
  static Mat4 scale(const Vec3& s);
  /// Rotation from a unit quaternion (x, y, z, w), as glTF stores it.
  static Mat4 rotate(float qx, float qy, float qz, float qw);
  bool isFinite() const;
};

Mat4 operator*(const Mat4& a, const Mat4& b);
/// Inverse computed in double; returns false if singular.
bool invert(const Mat4& a, Mat4& out);
Mat4 transpose(const Mat4& a);

/// An affine transform with its cached inverse.
struct Transform {
  Mat4 m, inv;
  Transform() = default;
  /// Throws tray::Error if m is singular or not finite.
  explicit Transform(const Mat4& matrix);

  Vec3 point(const Vec3& p) const { return transformPoint(m.m, p); }
  Vec3 vector(const Vec3& v) const { return transformVector(m.m, v); }
  /// Normals transform by the inverse transpose (stay perpendicular under non-uniform scale).
  Vec3 normal(const Vec3& n) const { return transformNormal(inv.m, n); }
  Vec3 inversePoint(const Vec3& p) const { return transformPoint(inv.m, p); }
  Vec3 inverseVector(const Vec3& v) const { return transformVector(inv.m, v); }
  Bounds3 bounds(const Bounds3& b) const;
  /// True when the transform flips handedness (negative determinant): triangle winding flips.
  bool swapsHandedness() const;
};

}  // namespace tray
