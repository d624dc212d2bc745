#include "core/transform.h"

#include "core/error.h"

namespace tray {

Mat4 Mat4::fromColumnMajor(const double* v) {
  Mat4 r;
  for (int c = 0; c < 4; ++c)
    for (int row = 0; row < 4; ++row) r.m[row][c] = static_cast<float>(v[c * 4 + row]);
  return r;
}

Mat4 Mat4::translate(const Vec3& t) {
  Mat4 r;
  r.m[0][3] = t.x;
  r.m[1][3] = t.y;
  r.m[2][3] = t.z;
  return r;
}

Mat4 Mat4::scale(const Vec3& s) {
  Mat4 r;
  r.m[0][0] = s.x;
  r.m[1][1] = s.y;
  r.m[2][2] = s.z;
  return r;
}

Mat4 Mat4::rotate(float x, float y, float z, float w) {
  Mat4 r;
  r.m[0][0] = 1 - 2 * (y * y + z * z);
  r.m[0][1] = 2 * (x * y - z * w);
  r.m[0][2] = 2 * (x * z + y * w);
  r.m[1][0] = 2 * (x * y + z * w);
  r.m[1][1] = 1 - 2 * (x * x + z * z);
  r.m[1][2] = 2 * (y * z - x * w);
  r.m[2][0] = 2 * (x * z - y * w);
  r.m[2][1] = 2 * (y * z + x * w);
  r.m[2][2] = 1 - 2 * (x * x + y * y);
  return r;
}

bool Mat4::isFinite() const {
  for (const auto& row : m)
    for (float v : row)
      if (!std::isfinite(v)) return false;
  return true;
}

Mat4 operator*(const Mat4& a, const Mat4& b) {
  Mat4 r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      double s = 0;
      for (int k = 0; k < 4; ++k) s += double(a.m[i][k]) * b.m[k][j];
      r.m[i][j] = static_cast<float>(s);
    }
  return r;
}

Mat4 transpose(const Mat4& a) {
  Mat4 r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) r.m[i][j] = a.m[j][i];
  return r;
}

bool invert(const Mat4& a, Mat4& out) {
  // Gauss-Jordan elimination with partial pivoting, in double.
  double t[4][8];
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      t[i][j] = a.m[i][j];
      t[i][j + 4] = i == j ? 1.0 : 0.0;
    }
  for (int c = 0; c < 4; ++c) {
    int pivot = c;
    for (int r = c + 1; r < 4; ++r)
      if (std::fabs(t[r][c]) > std::fabs(t[pivot][c])) pivot = r;
    if (std::fabs(t[pivot][c]) < 1e-30) return false;
    if (pivot != c)
      for (int j = 0; j < 8; ++j) std::swap(t[c][j], t[pivot][j]);
    double inv = 1.0 / t[c][c];
    for (int j = 0; j < 8; ++j) t[c][j] *= inv;
    for (int r = 0; r < 4; ++r) {
      if (r == c) continue;
      double f = t[r][c];
      if (f != 0)
        for (int j = 0; j < 8; ++j) t[r][j] -= f * t[c][j];
    }
  }
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) out.m[i][j] = static_cast<float>(t[i][j + 4]);
  return out.isFinite();
}

Transform::Transform(const Mat4& matrix) : m(matrix) {
  if (!m.isFinite()) throw Error("transform contains NaN or infinity");
  if (!invert(m, inv)) throw Error("transform is singular (zero scale)");
}

Bounds3 Transform::bounds(const Bounds3& b) const {
  if (b.empty()) return b;
  Bounds3 r;
  if (!b.finite()) {
    // Infinite extents stay infinite on every axis they can reach.
    r.lo = Vec3(-kInfinity);
    r.hi = Vec3(kInfinity);
    return r;
  }
  for (int i = 0; i < 8; ++i)
    r.extend(point({i & 1 ? b.hi.x : b.lo.x, i & 2 ? b.hi.y : b.lo.y, i & 4 ? b.hi.z : b.lo.z}));
  return r;
}

bool Transform::swapsHandedness() const {
  const auto& a = m.m;
  double det = a[0][0] * (double(a[1][1]) * a[2][2] - double(a[1][2]) * a[2][1]) -
               a[0][1] * (double(a[1][0]) * a[2][2] - double(a[1][2]) * a[2][0]) +
               a[0][2] * (double(a[1][0]) * a[2][1] - double(a[1][1]) * a[2][0]);
  return det < 0;
}

}  // namespace tray
