#pragma once
// Filtered texture lookups through OpenImageIO's TextureSystem: TRay does no image filtering
// of its own (docs/textures.md).
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

/// Owns a TextureSystem whose images are the scene's decoded TextureImages, served from memory
/// by a custom ImageInput with their MIP pyramids (TexturePyramid); OIIO filters. Thread-safe.
class TextureSampler {
 public:
  /// `images` must outlive the sampler (they are read in place, never copied by TRay).
  /// `cacheMB`: OIIO's tile cache budget (tray-render --texture-memory); 0: budgetFor(images).
  /// `oiioAutomip` (tests only): hand OIIO the finest level alone and let it make the others,
  /// the way TRay did before TexturePyramid (it then pins twice the finest level in memory).
  explicit TextureSampler(const std::vector<TextureImage>& images, double cacheMB = 0,
                          bool oiioAutomip = false);
  ~TextureSampler();
  TextureSampler(const TextureSampler&) = delete;
  TextureSampler& operator=(const TextureSampler&) = delete;

  /// RGB of ref's image at footprint f (in the reference's uv set, before its transform), with
  /// its sampler's wrap modes. A footprint under one texel magnifies (magFilter); a larger one
  /// minifies with minFilter: nearest/linear texels in the finest level, or one/two MIP levels.
  Color sample(const TextureRef& ref, const UvFootprint& f) const;

  /// The budget when none is given: every level of every image as OIIO's float tiles, so
  /// that no tile is ever evicted and made again, at least kMinCacheMB and at most a quarter
  /// of physical memory. OIIO allocates tiles as they are used, so a scene costs what it
  /// touches. Why not a fixed budget: the fixed 128 MB of before made DamagedHelmet (five
  /// 2048^2 textures, 336 MB of float levels) re-make evicted tiles from the codes through up
  /// to three computed levels, 10x slower at 160^2 and 64 spp (docs/textures.md, "Memory").
  static double budgetFor(const std::vector<TextureImage>& images);
  static constexpr int kMinCacheMB = 128;
  /// The budget in use (MB).
  double cacheMB() const;
  /// Tiles read again after the cache evicted them (OIIO's per-file stat:redundant_tiles,
  /// summed): 0 when the budget holds every tile used; each one costs a re-decode.
  int64_t tilesReadAgain() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tray
