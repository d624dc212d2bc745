#pragma once
// TRay's texture filter: what OpenImageIO 2.4.7's TextureSystem::texture computes for the
// options TRay uses (closest or bilinear texels; no MIP, one level or trilinear; clamp,
// periodic or mirror wrap), written again over TexturePyramid's texels with the same float
// operations in the same order, so the results are equal bit for bit
// (tests/textures/texture_lookup_test.cpp draws random lookups through both). Why not OIIO itself:
// its tile cache (hash lookups, locks, statistics) and generic sampler took about 40% of a path
// traced textured render (docs/textures.md, "Filtering").
#include "core/material.h"
#include "core/math.h"

namespace tray {

class TexturePyramid;

enum class TexelFilter { kClosest, kBilinear };         ///< OIIO's InterpClosest, InterpBilinear
enum class MipFilter { kNone, kOneLevel, kTrilinear };  ///< OIIO's MipModeNoMIP, ...

/// One lookup in OIIO's terms: (s, t) spans the image over [0, 1], t down from its first row
/// (glTF's v); the footprint is how (s, t) change per pixel step in x and in y.
struct TextureQuery {
  float s = 0, t = 0, dsdx = 0, dtdx = 0, dsdy = 0, dtdy = 0;
  TextureWrap wrapS = TextureWrap::kRepeat, wrapT = TextureWrap::kRepeat;
  TexelFilter texel = TexelFilter::kBilinear;
  MipFilter mip = MipFilter::kTrilinear;
};

/// The glTF filter as texel and MIP filters (docs/textures.md, "Filters").
void filtersOf(TextureFilter f, TexelFilter& texel, MipFilter& mip);

/// The filtered RGB of `pyramid` for `q`. Thread-safe (texels come from TexturePyramid::texel).
Color lookupTexture(const TexturePyramid& pyramid, const TextureQuery& q);

/// Prefetches the four level-0 texels that a bilinear lookup of q would read (those of a
/// closest one among them), for queries that read level 0 alone (no MIP filter: TextureSampler
/// knows). Reads nothing itself.
void prefetchLevel0(const TexturePyramid& pyramid, const TextureQuery& q);

}  // namespace tray
