#pragma once
// The MIP pyramid of a TextureImage, made by TRay the way OIIO's automip makes it, so that OIIO
// can be handed a MIP-mapped image. Why: for an image it automips, OIIO 2.4 raises its cache to
// twice the finest level (ImageCacheFile::read_unmipped calls set_min_cache_size), so an 8192^2
// texture pinned 1 GB of float tiles whatever max_memory_MB said. Every texel here is computed
// with OIIO's own expressions (read_unmipped: each level bilinearly samples the one below at
// its texel centres, OIIO::floorfrac and OIIO::bilerp from fmath.h), so the values OIIO filters
// are bit for bit those it made itself (tests/core/texture_pyramid_test.cpp compares both).
#include <cstdint>
#include <vector>

#include "core/texture_image.h"

namespace tray {

class TexturePyramid {
 public:
  /// `image` must outlive the pyramid. Levels 1..kComputed are computed from the level below
  /// whenever a row is asked for (from the compact codes, cheap); coarser levels, a 1/256 of
  /// the texels and less, are computed here once and stored as floats.
  explicit TexturePyramid(const TextureImage& image);

  static constexpr int kComputed = 3;

  /// OIIO's level count: halve (rounding down, at least 1) until 1 x 1.
  int levels() const { return int(width_.size()); }
  int width(int level) const { return width_[size_t(level)]; }
  int height(int level) const { return height_[size_t(level)]; }
  /// Row y of `level` as width(level) * 3 linear floats.
  void row(int level, int y, float* rgb) const;
  /// Bytes of the stored coarse levels.
  uint64_t storedBytes() const;

 private:
  void compute(int level, int y, float* rgb) const;

  const TextureImage& image_;
  std::vector<int> width_, height_;
  std::vector<std::vector<float>> stored_;  ///< per level; empty for levels 0..kComputed
};

}  // namespace tray
