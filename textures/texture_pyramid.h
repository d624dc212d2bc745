#pragma once
// The MIP pyramid of a TextureImage, made the way OIIO's automip makes it. Every texel is
// computed with OIIO's own expressions (ImageCacheFile::read_unmipped: each level bilinearly
// samples the one below at its texel centres, OIIO::floorfrac and OIIO::bilerp from fmath.h), so
// the values are bit for bit those OIIO made itself (tests/textures/texture_pyramid_test.cpp).
// Two readers: TRay's own filter (textures/texture_lookup.h) reads single texels through texel(),
// and OIIO's TextureSystem (the paged fallback and the tests' reference) reads rows through
// row(). Why a pyramid of TRay's own at all: for an image it automips, OIIO 2.4 pins twice the
// finest level in its cache (ImageCacheFile::read_unmipped calls set_min_cache_size).
#include <algorithm>
#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/texture_image.h"

namespace tray {

class TexturePyramid {
 public:
  /// `image` must outlive the pyramid. Levels 1..kComputed are made from the level below when
  /// asked for (cheap: from the compact codes); coarser levels, 1/256 of the texels and less,
  /// are computed here once and stored as floats.
  explicit TexturePyramid(const TextureImage& image);
  ~TexturePyramid();
  TexturePyramid(const TexturePyramid&) = delete;
  TexturePyramid& operator=(const TexturePyramid&) = delete;

  static constexpr int kComputed = 3;
  const TextureImage& image() const { return image_; }
  /// Side of the square tiles in which texel() keeps levels 1..kComputed (as OIIO's autotile).
  static constexpr int kTile = 64;

  /// OIIO's level count: halve (rounding down, at least 1) until 1 x 1.
  int levels() const { return int(levels_.size()); }
  int width(int level) const { return levels_[size_t(level)].width; }
  int height(int level) const { return levels_[size_t(level)].height; }

  /// Texel (x, y) of `level`, inside the level, as 3 linear floats. Level 0 is read from the
  /// image (codes through its table into `scratch`); levels 1..kComputed from 64 x 64 tiles
  /// made on first use and kept until the pyramid dies (one compare-exchange publishes a
  /// tile: no lock, and a racing thread's copy, equal bit for bit, is dropped); coarser ones
  /// from the stored floats. Thread-safe.
  const float* texel(int level, int x, int y, float scratch[3]) const {
    const Level& l = levels_[size_t(level)];
    if (level == 0) return texel0(x, y, scratch);
    if (l.stored) return l.stored + 3 * (size_t(y) * size_t(l.width) + size_t(x));
    const int tx = x / kTile, ty = y / kTile;
    const float* tile = this->tile(level, tx, ty);
    const int tileWidth = std::min(kTile, l.width - tx * kTile);
    return tile + 3 * (size_t(y - ty * kTile) * size_t(tileWidth) + size_t(x - tx * kTile));
  }

  /// Asks for the cache line of level 0's texel (x, y), inside the level, as texel() would
  /// read it (its float pixel, or its first code): a prefetch into L2, which neither faults
  /// nor changes a value.
  void prefetch0(int x, int y) const {
    const size_t p = size_t(y) * size_t(levels_[0].width) + size_t(x);
    const void* at =
        pixels_ ? static_cast<const void*>(pixels_ + 3 * p)
                : static_cast<const void*>(bytes_ + (wide_ ? 2 : 1) * p * size_t(channels_));
    __builtin_prefetch(at, 0, 2);
  }
  /// The four texels bilinear filtering blends, (xa, ya), (xb, ya), (xa, yb), (xb, yb) of
  /// `level` (>= 1, all inside it), into v[0..3] as texel() gives them, but with one dispatch
  /// on the level's store, and one tile lookup when the four share a tile. (Level 0 is read by
  /// texel(): sharing the row offsets of the codes measured no faster.)
  void texels2x2(int level, int xa, int xb, int ya, int yb, float scratch[4][3],
                 const float* v[4]) const {
    const Level& l = levels_[size_t(level)];
    if (l.stored) {
      const float* base = l.stored;
      const size_t rowA = size_t(ya) * size_t(l.width), rowB = size_t(yb) * size_t(l.width);
      v[0] = base + 3 * (rowA + size_t(xa)), v[1] = base + 3 * (rowA + size_t(xb));
      v[2] = base + 3 * (rowB + size_t(xa)), v[3] = base + 3 * (rowB + size_t(xb));
      return;
    }
    const int tx = xa / kTile, ty = ya / kTile;
    if (xb / kTile != tx || yb / kTile != ty) {  // across a tile edge, or wrapped
      for (int k = 0; k < 4; ++k) v[k] = texel(level, k & 1 ? xb : xa, k & 2 ? yb : ya, scratch[k]);
      return;
    }
    const float* tile = this->tile(level, tx, ty);
    const size_t tileWidth = size_t(std::min(kTile, l.width - tx * kTile));
    const size_t rowA = size_t(ya - ty * kTile) * tileWidth;
    const size_t rowB = size_t(yb - ty * kTile) * tileWidth;
    const size_t x0 = size_t(xa - tx * kTile), x1 = size_t(xb - tx * kTile);
    v[0] = tile + 3 * (rowA + x0), v[1] = tile + 3 * (rowA + x1);
    v[2] = tile + 3 * (rowB + x0), v[3] = tile + 3 * (rowB + x1);
  }

  /// Row y of `level` as width(level) * 3 linear floats, levels 1..kComputed computed from the
  /// levels below each time (OIIO's tile cache keeps what it reads; no tile here is touched).
  void row(int level, int y, float* rgb) const;

  /// Bytes of the stored coarse levels.
  uint64_t storedBytes() const;
  /// Bytes that texel()'s tiles take once every one is made: levels 1..kComputed as floats.
  static uint64_t tileBytesAtMost(int width, int height);
  /// Tiles texel() has made so far (each is made once, but for a lost race), and their bytes.
  int64_t tilesMade() const { return tilesMade_.load(std::memory_order_relaxed); }
  uint64_t tileBytes() const { return tileBytes_.load(std::memory_order_relaxed); }

 private:
  struct Level {
    int width = 0, height = 0, tilesX = 0;
    std::vector<float> storedTexels;                     ///< levels past kComputed
    const float* stored = nullptr;                       ///< storedTexels.data(), or null
    std::unique_ptr<std::atomic<const float*>[]> tiles;  ///< levels 1..kComputed
  };

  const float* texel0(int x, int y, float scratch[3]) const {
    const size_t p = size_t(y) * size_t(levels_[0].width) + size_t(x);
    if (pixels_) return pixels_ + 3 * p;
    const size_t k = p * size_t(channels_);
    const size_t g = channels_ >= 3 ? 1 : 0;  // grey replicates channel 0
    if (wide_) {
      auto at = [&](size_t i) {
        uint16_t v;
        __builtin_memcpy(&v, bytes_ + 2 * i, 2);
        return table_[v];
      };
      scratch[0] = at(k), scratch[1] = at(k + g), scratch[2] = at(k + 2 * g);
    } else {
      scratch[0] = table_[bytes_[k]], scratch[1] = table_[bytes_[k + g]],
      scratch[2] = table_[bytes_[k + 2 * g]];
    }
    return scratch;
  }
  const float* makeTile(int level, int tx, int ty) const;
  /// The tile (tx, ty) of a tiled level, made if missing.
  const float* tile(int level, int tx, int ty) const {
    const Level& l = levels_[size_t(level)];
    const float* t =
        l.tiles[size_t(ty) * size_t(l.tilesX) + size_t(tx)].load(std::memory_order_acquire);
    return t ? t : makeTile(level, tx, ty);
  }
  /// Texels [x0, x0 + w) x [y0, y0 + h) of `level` (>= 1) into `out` (row j at out + j *
  /// stride floats), computed from the level below read as one block (readBlock): through
  /// its tiles when `fromTiles`, else computed the same way in turn.
  void computeBlock(int level, int x0, int y0, int w, int h, float* out, size_t stride,
                    bool fromTiles) const;
  /// Texels [x0, x0 + w) x [y0, y0 + h) of `level`, all inside it, into `out` (row stride
  /// `stride` floats): level 0 from its floats or codes, stored levels copied, tiled levels
  /// from their tiles or computed (computeBlock).
  void readBlock(int level, int x0, int y0, int w, int h, float* out, size_t stride,
                 bool fromTiles) const;
  void readLevel0(int x0, int y0, int w, int h, float* out, size_t stride) const;

  const TextureImage& image_;
  std::vector<Level> levels_;
  // Level 0 as texel0 reads it: float pixels, or codes and their table.
  const float* pixels_ = nullptr;
  const unsigned char* bytes_ = nullptr;
  const float* table_ = nullptr;
  int channels_ = 3;
  bool wide_ = false;
  mutable std::atomic<int64_t> tilesMade_{0};
  mutable std::atomic<uint64_t> tileBytes_{0};
};

}  // namespace tray
