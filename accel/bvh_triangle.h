#pragma once
// Ray–triangle tests, two-sided like Embree's. Barycentrics follow Embree's convention:
// p = (1 - b1 - b2) p0 + b1 p1 + b2 p2.
#include <cmath>
#include <utility>

#include "core/math.h"

namespace tray {

/// Per-ray set-up of the watertight test: Woop, Benthin & Wald, "Watertight Ray/Triangle
/// Intersection", JCGT 2(1), 2013, section 3. The ray is sheared so it runs along +z; then the
/// edge tests are 2D and a point exactly on a shared edge gets the same edge value (zero) from
/// both triangles, so it can never miss both.
struct WatertightRay {
  Vec3 o;
  int kx = 0, ky = 1, kz = 2;
  float sx = 0, sy = 0, sz = 1;
};

inline WatertightRay prepareWatertight(const Vec3& o, const Vec3& d) {
  WatertightRay r;
  r.o = o;
  Vec3 ad = abs(d);
  r.kz = ad.x > ad.y ? (ad.x > ad.z ? 0 : 2) : (ad.y > ad.z ? 1 : 2);
  r.kx = (r.kz + 1) % 3;
  r.ky = (r.kx + 1) % 3;
  if (d[r.kz] < 0) std::swap(r.kx, r.ky);  // keep the winding
  r.sx = d[r.kx] / d[r.kz];
  r.sy = d[r.ky] / d[r.kz];
  r.sz = 1.0f / d[r.kz];
  return r;
}

/// Watertight test (Woop et al. 2013, fig. 4 without back-face culling). Hit when t lies in
/// (tmin, tmax).
inline bool intersectWatertight(const WatertightRay& r, const Vec3& p0, const Vec3& p1,
                                const Vec3& p2, float tmin, float tmax, float& t, float& b1,
                                float& b2) {
  const Vec3 a = p0 - r.o, b = p1 - r.o, c = p2 - r.o;
  const float ax = a[r.kx] - r.sx * a[r.kz], ay = a[r.ky] - r.sy * a[r.kz];
  const float bx = b[r.kx] - r.sx * b[r.kz], by = b[r.ky] - r.sy * b[r.kz];
  const float cx = c[r.kx] - r.sx * c[r.kz], cy = c[r.ky] - r.sy * c[r.kz];
  float u = cx * by - cy * bx;
  float v = ax * cy - ay * cx;
  float w = bx * ay - by * ax;
  // An edge value of exactly zero is resolved in double precision (section 3.3), so the sign
  // tests of the two triangles sharing that edge agree.
  if (u == 0.0f || v == 0.0f || w == 0.0f) {
    u = float(double(cx) * double(by) - double(cy) * double(bx));
    v = float(double(ax) * double(cy) - double(ay) * double(cx));
    w = float(double(bx) * double(ay) - double(by) * double(ax));
  }
  if ((u < 0 || v < 0 || w < 0) && (u > 0 || v > 0 || w > 0)) return false;
  const float det = u + v + w;
  if (det == 0.0f) return false;
  const float az = r.sz * a[r.kz], bz = r.sz * b[r.kz], cz = r.sz * c[r.kz];
  const float tScaled = u * az + v * bz + w * cz;
  const float rcpDet = 1.0f / det;
  const float tt = tScaled * rcpDet;
  if (!(tt > tmin && tt < tmax)) return false;
  t = tt;
  b1 = v * rcpDet;
  b2 = w * rcpDet;
  return true;
}

/// Möller & Trumbore, "Fast, Minimum Storage Ray/Triangle Intersection", JGT 2(1), 1997: the
/// seed's test. Not watertight: the edge tests of two triangles sharing an edge are computed
/// from different cross products, so a ray through the edge can miss both (see
/// tests/accel/bvh_triangle_test.cpp).
inline bool intersectMollerTrumbore(const Vec3& o, const Vec3& d, const Vec3& p0, const Vec3& p1,
                                    const Vec3& p2, float tmin, float tmax, float& t, float& b1,
                                    float& b2) {
  const Vec3 e1 = p1 - p0, e2 = p2 - p0;
  const Vec3 pv = cross(d, e2);
  const float det = dot(e1, pv);
  if (det == 0.0f) return false;
  const float inv = 1.0f / det;
  const Vec3 tv = o - p0;
  const float u = dot(tv, pv) * inv;
  if (u < 0.0f || u > 1.0f) return false;
  const Vec3 qv = cross(tv, e1);
  const float v = dot(d, qv) * inv;
  if (v < 0.0f || u + v > 1.0f) return false;
  const float tt = dot(e2, qv) * inv;
  if (!(tt > tmin && tt < tmax)) return false;
  t = tt;
  b1 = u;
  b2 = v;
  return true;
}

}  // namespace tray
