#pragma once
// OpenImageIO's TextureSystem over TRay's texture pyramids: the paged fallback for scenes whose
// MIP tiles would exceed --texture-memory, and the reference that tests compare TRay's own
// filter (textures/texture_lookup.h) with. Its tile cache holds at most `cacheMB`, evicting tiles
// and making them again from the pyramid's rows, which changes time, never values.
#include <cstdint>
#include <memory>
#include <vector>

#include "textures/texture_lookup.h"
#include "textures/texture_pyramid.h"

namespace tray {

class OiioTextureSystem {
 public:
  /// `pyramids` must outlive this. `automip` (tests only): hand OIIO each finest level alone
  /// and let it make the others, as TRay did before TexturePyramid.
  OiioTextureSystem(const std::vector<std::unique_ptr<TexturePyramid>>& pyramids, double cacheMB,
                    bool automip = false);
  ~OiioTextureSystem();
  OiioTextureSystem(const OiioTextureSystem&) = delete;
  OiioTextureSystem& operator=(const OiioTextureSystem&) = delete;

  /// TextureSystem::texture on image `index` with q's options; false if OIIO failed.
  bool lookup(size_t index, const TextureQuery& q, float rgb[3]) const;
  /// OIIO's max_memory_MB.
  double cacheMB() const;
  /// Tiles read again after the cache evicted them (OIIO's per-file stat:redundant_tiles).
  int64_t tilesReadAgain() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tray
