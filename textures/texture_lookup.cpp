#include "textures/texture_lookup.h"

#include <OpenImageIO/fmath.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>

#include "textures/texture_pyramid.h"

// Every expression below follows OIIO 2.4.7's src/libtexture/texturesys.cpp (and the wrap
// functions of src/libOpenImageIO/imageio.cpp) operation for operation; Debian's libOpenImageIO
// is built for plain x86-64 (SSE2, no FMA), and this file is compiled with -ffp-contract=off
// (core/CMakeLists.txt) so that no multiply-add is fused here either.

namespace tray {

namespace {

/// OIIO::floorfrac (fmath.h) with its int conversion defined: OIIO's int(f) compiles to x86's
/// cvttss2si / cvttps2dq, which give INT_MIN for NaN and beyond int's range; so does this.
inline float floorFrac(float x, int* xint) {
  const float f = std::floor(x);
  *xint = f >= -2147483648.0f && f < 2147483648.0f ? int(f) : INT_MIN;
  return x - f;
}

/// OIIO's wrap_clamp, wrap_periodic (its wrap_periodic_pow2 gives the same texel for
/// power-of-two sizes, and so does the mask here) and wrap_mirror, with origin 0. The mirror
/// runs in 64 bits where OIIO's int overflows (coord = INT_MIN), to the value the overflow
/// gives on x86 (INT_MAX).
inline int wrap(int coord, int size, TextureWrap mode) {
  switch (mode) {
    case TextureWrap::kClampToEdge:
      return coord < 0 ? 0 : coord >= size ? size - 1 : coord;
    case TextureWrap::kMirroredRepeat: {
      int64_t c = coord < 0 ? -int64_t(coord) - 1 : coord;
      const int64_t iter = c / size;  // which repetition of the pattern
      c -= iter * size;
      return int(iter & 1 ? size - 1 - c : c);
    }
    case TextureWrap::kRepeat:
      break;
  }
  if ((size & (size - 1)) == 0) return coord & (size - 1);
  const int c = coord % size;
  return c < 0 ? c + size : c;
}

/// The 2 x 2 texels of `level` that a bilinear lookup of q blends (st_to_texel_simd: texel
/// centres at +0.5; each wrapped), and its weights' fractions.
struct BilinearTexels {
  int xa, xb, ya, yb;
  float sfrac, tfrac;
};
BilinearTexels bilinearTexels(const TexturePyramid& p, int level, const TextureQuery& q) {
  const int w = p.width(level), h = p.height(level);
  int s0, t0;
  const float sfrac = floorFrac(q.s * float(w) - 0.5f, &s0);
  const float tfrac = floorFrac(q.t * float(h) - 0.5f, &t0);
  BilinearTexels t;
  t.xa = wrap(s0, w, q.wrapS), t.xb = wrap(s0 + 1, w, q.wrapS);
  t.ya = wrap(t0, h, q.wrapT), t.yb = wrap(t0 + 1, h, q.wrapT);
  t.sfrac = sfrac, t.tfrac = tfrac;
  return t;
}

/// sample_bilinear for one sample of weight 1: the four texels of bilinearTexels,
/// OIIO::bilerp, added to a zero accumulator.
void bilinear(const TexturePyramid& p, int level, const TextureQuery& q, float out[3]) {
  const auto [xa, xb, ya, yb, sfrac, tfrac] = bilinearTexels(p, level, q);
  float scratch[4][3];
  const float* v[4];
  if (level == 0) {
    v[0] = p.texel(0, xa, ya, scratch[0]), v[1] = p.texel(0, xb, ya, scratch[1]);
    v[2] = p.texel(0, xa, yb, scratch[2]), v[3] = p.texel(0, xb, yb, scratch[3]);
  } else {
    p.texels2x2(level, xa, xb, ya, yb, scratch, v);
  }
  const float *v0 = v[0], *v1 = v[1], *v2 = v[2], *v3 = v[3];
  const float s1 = 1.0f - sfrac, t1 = 1.0f - tfrac;
  for (int c = 0; c < 3; ++c)
    out[c] = 0.0f + (t1 * (v0[c] * s1 + v1[c] * sfrac) + tfrac * (v2[c] * s1 + v3[c] * sfrac));
}

/// sample_closest for one sample of weight 1: st_to_texel, then the nearer texel per axis.
void closest(const TexturePyramid& p, int level, const TextureQuery& q, float out[3]) {
  const int w = p.width(level), h = p.height(level);
  int x, y;
  const float sfrac = floorFrac(q.s * float(w) - 0.5f, &x);
  const float tfrac = floorFrac(q.t * float(h) - 0.5f, &y);
  if (sfrac > 0.5f) ++x;
  if (tfrac > 0.5f) ++y;
  float scratch[3];
  const float* v = p.texel(level, wrap(x, w, q.wrapS), wrap(y, h, q.wrapT), scratch);
  for (int c = 0; c < 3; ++c) out[c] = 0.0f + v[c];
}

void sampleLevel(const TexturePyramid& p, int level, const TextureQuery& q, float out[3]) {
  if (q.texel == TexelFilter::kClosest)
    closest(p, level, q, out);
  else
    bilinear(p, level, q, out);
}

struct LevelBlend {
  int level[2] = {-1, -1};
  float weight[2] = {0, 0};
};

/// The filter width of texture_lookup_trilinear_mipmap: adjust_width (swidth = twidth = 1)
/// gives degenerate derivatives a length of 1e-8, then the larger of the s and t extents
/// (conservative_filter, OIIO's default), plus a blur of 0.
float filterWidth(const TextureQuery& q) {
  float dsdx = q.dsdx, dtdx = q.dtdx, dsdy = q.dsdy, dtdy = q.dtdy;
  static const float eps = 1.0e-8f, eps2 = eps * eps;
  const float dxlen2 = dsdx * dsdx + dtdx * dtdx;
  const float dylen2 = dsdy * dsdy + dtdy * dtdy;
  if (dxlen2 < eps2) {
    if (dylen2 < eps2) {
      dsdx = eps, dsdy = 0, dtdx = 0, dtdy = eps;
    } else {
      const float scale = eps / sqrtf(dylen2);
      dsdx = dtdy * scale;
      dtdx = -dsdy * scale;
    }
  } else if (dylen2 < eps2) {
    const float scale = eps / sqrtf(dxlen2);
    dsdy = -dtdx * scale;
    dtdy = dsdx * scale;
  }
  const float sfilt = std::max(std::fabs(dsdx), std::fabs(dsdy));
  const float tfilt = std::max(std::fabs(dtdx), std::fabs(dtdy));
  return std::max(sfilt, tfilt) + 0.0f;
}

/// compute_miplevels: the first level where the filter spans at most one texel of the
/// level's smaller side, blended with the one above by 2 * width - 1.
LevelBlend chooseLevels(const TexturePyramid& p, const TextureQuery& q) {
  const float filtwidth = filterWidth(q);
  LevelBlend b;
  const int n = p.levels();
  for (int m = 0; m < n; ++m) {
    const float ras = filtwidth * float(std::min(p.width(m), p.height(m)));
    if (ras <= 1.0f) {
      const float blend = OIIO::clamp(2.0f * ras - 1.0f, 0.0f, 1.0f);
      b = {{m - 1, m}, {1.0f - blend, blend}};
      break;
    }
  }
  if (b.level[1] < 0) return {{n - 1, n - 1}, {1.0f, 0.0f}};  // coarser than the 1x1 level
  if (b.level[0] < 0) return {{0, 0}, {1.0f, 0.0f}};          // finer than level 0
  if (q.mip == MipFilter::kOneLevel) return {{b.level[1], b.level[1]}, {1.0f, 0.0f}};
  return b;
}

}  // namespace

void filtersOf(TextureFilter f, TexelFilter& texel, MipFilter& mip) {
  using F = TextureFilter;
  const bool nearestTexel =
      f == F::kNearest || f == F::kNearestMipmapNearest || f == F::kNearestMipmapLinear;
  texel = nearestTexel ? TexelFilter::kClosest : TexelFilter::kBilinear;
  switch (f) {
    case F::kNearest:
    case F::kLinear:
      mip = MipFilter::kNone;
      break;
    case F::kNearestMipmapNearest:
    case F::kLinearMipmapNearest:
      mip = MipFilter::kOneLevel;
      break;
    case F::kNearestMipmapLinear:
    case F::kLinearMipmapLinear:
      mip = MipFilter::kTrilinear;
      break;
  }
}

Color lookupTexture(const TexturePyramid& p, const TextureQuery& q) {
  float rgb[3];
  if (q.mip == MipFilter::kNone) {  // texture_lookup_nomip: level 0, the sampler's sum as is
    sampleLevel(p, 0, q, rgb);
    return {rgb[0], rgb[1], rgb[2]};
  }
  // texture_lookup_trilinear_mipmap: levels of weight 0 are skipped; the others are summed,
  // each times its weight, onto 0.
  const LevelBlend b = chooseLevels(p, q);
  float sum[3] = {0, 0, 0};
  for (int i = 0; i < 2; ++i) {
    if (!b.weight[i]) continue;
    sampleLevel(p, b.level[i], q, rgb);
    for (int c = 0; c < 3; ++c) sum[c] += b.weight[i] * rgb[c];
  }
  return {sum[0], sum[1], sum[2]};
}

void prefetchLevel0(const TexturePyramid& p, const TextureQuery& q) {
  const BilinearTexels t = bilinearTexels(p, 0, q);
  p.prefetch0(t.xa, t.ya), p.prefetch0(t.xb, t.ya);
  p.prefetch0(t.xa, t.yb), p.prefetch0(t.xb, t.yb);
}

}  // namespace tray
