#pragma once
// Filtered texture lookups: the glTF sampler and KHR_texture_transform turned into a lookup of
// TRay's own filter (textures/texture_lookup.h, OIIO 2.4.7's arithmetic over lazily made MIP
// tiles), or of OpenImageIO's TextureSystem when the scene's MIP tiles would exceed the texture
// memory budget (its cache pages them). Both give the same values bit for bit (docs/textures.md).
#include <memory>
#include <vector>

#include "core/material.h"
#include "core/math.h"
#include "core/scene.h"

namespace tray {

/// A point in a texture's uv space with its footprint: how uv changes per pixel step in x
/// and in y (zero = a point sample, bilinear in the finest level).
struct UvFootprint {
  Vec2 uv, dx, dy;
};

/// KHR_texture_transform: uv' = T R S uv (the extension's README; rotation turns uvs
/// counter-clockwise). `vector` applies only the linear part, for footprint derivatives.
Vec2 transformUv(const TextureRef& ref, Vec2 uv, bool vector = false);

/// Which implementation filters. kAuto: TRay's own unless the scene's MIP tiles could exceed
/// the budget; the others force one (tests, benchmarks).
enum class TextureBackend { kAuto, kTray, kOiio, kOiioAutomip };

/// Owns the scene's texture pyramids and filters lookups in them. Thread-safe.
class TextureSampler {
 public:
  /// `images` must outlive the sampler (they are read in place, never copied by TRay).
  /// `cacheMB`: the texture memory budget (tray-render --texture-memory); 0: budgetFor(images).
  /// kOiioAutomip (tests only): OIIO makes the MIP levels itself from the finest one, the way
  /// TRay did before TexturePyramid (it then pins twice the finest level in memory).
  explicit TextureSampler(const std::vector<TextureImage>& images, double cacheMB = 0,
                          TextureBackend backend = TextureBackend::kAuto);
  ~TextureSampler();
  TextureSampler(const TextureSampler&) = delete;
  TextureSampler& operator=(const TextureSampler&) = delete;

  /// RGB of ref's image at footprint f (in the reference's uv set, before its transform), with
  /// its sampler's wrap modes. A footprint under one texel magnifies (magFilter); a larger one
  /// minifies with minFilter: nearest/linear texels in the finest level, or one/two MIP levels.
  Color sample(const TextureRef& ref, const UvFootprint& f) const;
  /// Prefetches what sample(ref, {uv}) will read, where that is known from uv alone: TRay's
  /// filter on a reference whose footprint does not matter (level 0 only). Otherwise nothing.
  /// The wavefront calls it for a whole queue before shading it, so that the texel misses of
  /// many vertices overlap (docs/textures.md, "Prefetching").
  void prefetch(const TextureRef& ref, Vec2 uv) const;

  /// False when ref's footprint changes nothing: its min and mag filters are the same filter
  /// without MIP levels (NEAREST or LINEAR both ways), so the footprint neither chooses between
  /// them nor picks a level. sample() then reads f.uv alone, and callers may skip computing
  /// f.dx and f.dy.
  static bool footprintMatters(const TextureRef& ref) {
    return ref.minFilter != ref.magFilter ||
           (ref.magFilter != TextureFilter::kNearest && ref.magFilter != TextureFilter::kLinear);
  }

  /// The budget when none is given: every level of every image as OIIO's float tiles, at
  /// least kMinCacheMB and at most a quarter of physical memory. Why not a fixed budget: the
  /// fixed 128 MB of before made DamagedHelmet (five 2048^2 textures, 336 MB of float levels)
  /// re-make evicted OIIO tiles, 10x slower at 160^2 and 64 spp (docs/textures.md, "Memory").
  static double budgetFor(const std::vector<TextureImage>& images);
  static constexpr int kMinCacheMB = 128;
  /// What TRay's own filter can allocate at most: every MIP tile it makes on demand (levels
  /// 1..TexturePyramid::kComputed as floats), in MB. It is used when this fits the budget.
  static double tileMBAtMost(const std::vector<TextureImage>& images);

  /// The budget in use (MB).
  double cacheMB() const { return cacheMB_; }
  /// True when OpenImageIO's TextureSystem filters (its cache pages tiles within cacheMB()).
  bool paged() const;
  /// Tiles OIIO read again after its cache evicted them (stat:redundant_tiles, summed);
  /// 0 for TRay's own filter, whose tiles are made once and never evicted.
  int64_t tilesReadAgain() const;
  /// MIP tiles TRay's own filter has made so far (TexturePyramid::tilesMade, summed).
  int64_t tilesMade() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  double cacheMB_ = 0;
};

}  // namespace tray
