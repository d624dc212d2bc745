#pragma once
// Four triangles tested at once by the watertight test of accel/bvh_triangle.h (Woop, Benthin &
// Wald, JCGT 2013): the leaf layout of the mesh trees. Each lane does exactly the scalar test's
// arithmetic, so hits, t and barycentrics are bit-for-bit those of intersectWatertight (and thus
// agree with Embree's robust mode as the scalar test does).
#include <cstdint>

#include "accel/bvh_triangle.h"
#include "accel/simd4.h"
#include "core/hit.h"

namespace tray {

/// Structure of arrays: p[vertex][axis][lane]. Unused lanes hold NaN vertices, which every
/// comparison below rejects (the t range test is false for NaN), and index kNoTriangle.
struct alignas(16) Triangle4 {
  static constexpr uint32_t kNoTriangle = 0xffffffffu;
  float p[3][3][4];
  uint32_t index[4];  ///< triangle index within the mesh
  Vec3 vertex(int v, int lane) const { return {p[v][0][lane], p[v][1][lane], p[v][2][lane]}; }
};
static_assert(sizeof(Triangle4) == 160);

/// The per-ray constants of the watertight test in all four lanes.
struct WatertightRay4 {
  WatertightRay scalar;
  simd::F4 ox, oy, oz, sx, sy, sz;
};

inline WatertightRay4 prepareWatertight4(const Vec3& o, const Vec3& d) {
  WatertightRay4 r;
  r.scalar = prepareWatertight(o, d);
  const WatertightRay& s = r.scalar;
  r.ox = simd::set1(o[s.kx]), r.oy = simd::set1(o[s.ky]), r.oz = simd::set1(o[s.kz]);
  r.sx = simd::set1(s.sx), r.sy = simd::set1(s.sy), r.sz = simd::set1(s.sz);
  return r;
}

/// Bit i of the result is set when lane i is hit with t in (tmin, tmax); t, b1, b2 receive the
/// lanes' values (meaningful for hit lanes only).
[[gnu::always_inline]] inline int intersectWatertight4(const WatertightRay4& r,
                                                       const Triangle4& tri, float tmin, float tmax,
                                                       float t[4], float b1[4], float b2[4]) {
  using namespace simd;
  const int kx = r.scalar.kx, ky = r.scalar.ky, kz = r.scalar.kz;
  // Vertices relative to the origin, sheared so the ray runs along +z (paper, fig. 4).
  const F4 az0 = load(tri.p[0][kz]) - r.oz, bz0 = load(tri.p[1][kz]) - r.oz,
           cz0 = load(tri.p[2][kz]) - r.oz;
  const F4 ax = (load(tri.p[0][kx]) - r.ox) - r.sx * az0;
  const F4 ay = (load(tri.p[0][ky]) - r.oy) - r.sy * az0;
  const F4 bx = (load(tri.p[1][kx]) - r.ox) - r.sx * bz0;
  const F4 by = (load(tri.p[1][ky]) - r.oy) - r.sy * bz0;
  const F4 cx = (load(tri.p[2][kx]) - r.ox) - r.sx * cz0;
  const F4 cy = (load(tri.p[2][ky]) - r.oy) - r.sy * cz0;
  const F4 u = cx * by - cy * bx;
  const F4 v = ax * cy - ay * cx;
  const F4 w = bx * ay - by * ax;
  const F4 zero = set1(0.0f);
  const int negative = bits((u < zero) | (v < zero) | (w < zero));
  const int positive = bits((u > zero) | (v > zero) | (w > zero));
  const int onEdge = bits((u == zero) | (v == zero) | (w == zero));
  const F4 det = u + v + w;
  const F4 tScaled = u * (r.sz * az0) + v * (r.sz * bz0) + w * (r.sz * cz0);
  const F4 rcpDet = set1(1.0f) / det;
  const F4 tt = tScaled * rcpDet;
  int mask = ~(negative & positive) & ~bits(det == zero) &
             bits((tt > set1(tmin)) & (tt < set1(tmax))) & ~onEdge & 15;
  store(t, tt);
  store(b1, v * rcpDet);
  store(b2, w * rcpDet);
  // An edge value of exactly zero is resolved in double precision by the scalar test (paper,
  // section 3.3); it is rare, so those lanes simply take the scalar path.
  for (int edge = onEdge & 15; edge; edge &= edge - 1) {
    int i = __builtin_ctz(unsigned(edge));
    if (intersectWatertight(r.scalar, tri.vertex(0, i), tri.vertex(1, i), tri.vertex(2, i), tmin,
                            tmax, t[i], b1[i], b2[i]))
      mask |= 1 << i;
  }
  return mask;
}

/// The closest-hit step over a block's hit lanes (`mask`, with intersectWatertight4's t, b1,
/// b2): lanes in order with a strict test, so that the first of equally near triangles wins, as
/// when they are tested one by one. Each accepted lane nearer than tmax lowers tmax and
/// becomes `hit`; true if any did.
template <class Accept>
[[gnu::always_inline]] inline bool closestLane(const Triangle4& block, int mask, const float* t,
                                               const float* b1, const float* b2, float& tmax,
                                               Hit& hit, const Accept& accept) {
  bool found = false;
  for (; mask; mask &= mask - 1) {
    const int i = __builtin_ctz(unsigned(mask));
    if (!(t[i] < tmax) || !accept(block.index[i], b1[i], b2[i])) continue;
    tmax = t[i];
    hit = Hit{};
    hit.t = t[i];
    hit.triangle = block.index[i];
    hit.b1 = b1[i];
    hit.b2 = b2[i];
    found = true;
  }
  return found;
}

/// The any-hit step over a block's hit lanes: true if `accept` takes one of them (an alpha test).
template <class Accept>
[[gnu::always_inline]] inline bool anyLaneAccepted(const Triangle4& block, int mask,
                                                   const float* b1, const float* b2,
                                                   const Accept& accept) {
  for (; mask; mask &= mask - 1) {
    const int i = __builtin_ctz(unsigned(mask));
    if (accept(block.index[i], b1[i], b2[i])) return true;
  }
  return false;
}

}  // namespace tray
