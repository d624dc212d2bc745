#include "textures/texture_pyramid.h"

#include <OpenImageIO/fmath.h>
#include <tbb/parallel_for.h>

#include <climits>
#include <cstring>

namespace tray {

namespace {

/// Where texel i of a level of `size` texels samples the finer level of `upSize`: the lower
/// texel in *low and the weight of the upper one. OIIO's read_unmipped expression: the texel
/// centre (i + 0.5) / size in [0, 1], scaled to the finer level, minus half a texel (in double,
/// as OIIO writes it, then rounded to float by floorfrac).
float sourceTexel(int i, int size, int upSize, int* low) {
  const float f = (i + 0.5f) / float(size);
  return OIIO::floorfrac(f * upSize - 0.5, low);
}

/// Width and height of the blocks in which the stored levels are computed: wide, so that the
/// first stored level reads level 0 in long runs of a row (16 kBlockWidth texels).
constexpr int kBlockWidth = 128, kBlockHeight = 4;

}  // namespace

TexturePyramid::TexturePyramid(const TextureImage& image) : image_(image) {
  int w = image.width, h = image.height;
  auto addLevel = [&] {
    levels_.emplace_back();
    levels_.back().width = w, levels_.back().height = h;
  };
  addLevel();
  while (w > 1 || h > 1) {  // ImageCacheFile::open, automip
    w = std::max(1, w / 2);
    h = std::max(1, h / 2);
    addLevel();
  }
  if (image.codes) {
    bytes_ = image.codes->bytes.data();
    table_ = image.table->data();
    channels_ = image.codes->channels;
    wide_ = image.codes->wide;
  } else {
    pixels_ = image.pixels.data();
  }
  for (int level = 1; level < levels(); ++level) {
    Level& l = levels_[size_t(level)];
    if (level <= kComputed) {
      l.tilesX = (l.width + kTile - 1) / kTile;
      const size_t tiles = size_t(l.tilesX) * size_t((l.height + kTile - 1) / kTile);
      l.tiles = std::make_unique<std::atomic<const float*>[]>(tiles);
      for (size_t t = 0; t < tiles; ++t) l.tiles[t].store(nullptr, std::memory_order_relaxed);
      continue;
    }
    // In blocks, each computed from blocks of the levels below (no tile is made).
    const size_t rowFloats = size_t(l.width) * 3;
    std::vector<float> texels(rowFloats * size_t(l.height));
    const int blocksX = (l.width + kBlockWidth - 1) / kBlockWidth;
    const int blocksY = (l.height + kBlockHeight - 1) / kBlockHeight;
    tbb::parallel_for(0, blocksX * blocksY, [&](int b) {
      const int x0 = b % blocksX * kBlockWidth, y0 = b / blocksX * kBlockHeight;
      computeBlock(level, x0, y0, std::min(kBlockWidth, l.width - x0),
                   std::min(kBlockHeight, l.height - y0),
                   texels.data() + size_t(y0) * rowFloats + 3 * size_t(x0), rowFloats, false);
    });
    l.storedTexels = std::move(texels);
    l.stored = l.storedTexels.data();
  }
}

TexturePyramid::~TexturePyramid() {
  for (Level& l : levels_) {
    if (!l.tiles) continue;
    const size_t tiles = size_t(l.tilesX) * size_t((l.height + kTile - 1) / kTile);
    for (size_t t = 0; t < tiles; ++t) delete[] l.tiles[t].load(std::memory_order_relaxed);
  }
}

void TexturePyramid::row(int level, int y, float* rgb) const {
  if (level == 0) return image_.row(y, rgb);
  const Level& l = levels_[size_t(level)];
  if (!l.stored) return computeBlock(level, 0, y, l.width, 1, rgb, size_t(l.width) * 3, false);
  const size_t n = size_t(l.width) * 3;
  std::memcpy(rgb, l.stored + size_t(y) * n, n * sizeof(float));
}

namespace {

/// Where texels [first, first + n) of a level of `size` texels sample the finer level of
/// `upSize` (sourceTexel for each): the lower texels, monotonic, and the upper ones' weights.
struct Taps {
  std::vector<int> low;
  std::vector<float> frac;
  /// Every tap two texels past the one before with the same weight: a level that halves the
  /// finer one exactly (a power-of-two size gives weight 0.5 everywhere), whose rows are then
  /// filtered without reading low and frac per texel.
  bool even = true;
  Taps(int first, int n, int size, int upSize) : low(size_t(n)), frac(size_t(n)) {
    for (int i = 0; i < n; ++i) {
      frac[size_t(i)] = sourceTexel(first + i, size, upSize, &low[size_t(i)]);
      even = even && low[size_t(i)] == low[0] + 2 * i && frac[size_t(i)] == frac[0];
    }
  }
};

/// Zeroes the texels of a w x h block of RGB floats outside [xa, xb) x [ya, yb).
void zeroOutside(float* block, int w, int h, int xa, int xb, int ya, int yb) {
  const size_t stride = size_t(w) * 3;
  for (int y = 0; y < h; ++y) {
    float* row = block + size_t(y) * stride;
    if (y < ya || y >= yb || xa >= xb) {
      std::fill(row, row + stride, 0.0f);
      continue;
    }
    std::fill(row, row + 3 * size_t(xa), 0.0f);
    std::fill(row + 3 * size_t(xb), row + stride, 0.0f);
  }
}

}  // namespace

void TexturePyramid::readLevel0(int x0, int y0, int w, int h, float* out, size_t stride) const {
  const size_t width0 = size_t(levels_[0].width);
  for (int j = 0; j < h; ++j, out += stride) {
    const size_t first = size_t(y0 + j) * width0 + size_t(x0);
    image_.texels(first, w, out);
    // The same run two rows down, which a tile or block reads next: short strided runs are
    // what the hardware prefetcher misses.
    const size_t bytesPerTexel = size_t(channels_) * (wide_ ? 2 : 1);
    const size_t ahead = size_t(y0 + j + 2) * width0 + size_t(x0);
    if (!pixels_ && y0 + j + 2 < levels_[0].height)
      for (size_t b = 0; b < size_t(w) * bytesPerTexel; b += 64)
        __builtin_prefetch(bytes_ + ahead * bytesPerTexel + b);
  }
}

void TexturePyramid::readBlock(int level, int x0, int y0, int w, int h, float* out, size_t stride,
                               bool fromTiles) const {
  if (level == 0) return readLevel0(x0, y0, w, h, out, stride);
  const Level& l = levels_[size_t(level)];
  if (l.stored) {
    for (int j = 0; j < h; ++j)
      std::memcpy(out + size_t(j) * stride,
                  l.stored + 3 * (size_t(y0 + j) * size_t(l.width) + size_t(x0)),
                  size_t(w) * 3 * sizeof(float));
    return;
  }
  if (!fromTiles) return computeBlock(level, x0, y0, w, h, out, stride, false);
  // Row segments of each tile the block overlaps.
  for (int ty = y0 / kTile; ty * kTile < y0 + h; ++ty)
    for (int tx = x0 / kTile; tx * kTile < x0 + w; ++tx) {
      const float* t = tile(level, tx, ty);
      const int tileX = tx * kTile, tileY = ty * kTile;
      const int tileWidth = std::min(kTile, l.width - tileX);
      const int xa = std::max(x0, tileX), xb = std::min(x0 + w, tileX + tileWidth);
      const int ya = std::max(y0, tileY), yb = std::min(y0 + h, tileY + kTile);
      for (int y = ya; y < yb; ++y)
        std::memcpy(out + size_t(y - y0) * stride + 3 * size_t(xa - x0),
                    t + 3 * (size_t(y - tileY) * size_t(tileWidth) + size_t(xa - tileX)),
                    size_t(xb - xa) * 3 * sizeof(float));
    }
}

void TexturePyramid::computeBlock(int level, int x0, int y0, int w, int h, float* out,
                                  size_t stride, bool fromTiles) const {
  // OIIO's read_unmipped, texel by texel, with the same float expressions (sourceTexel and
  // OIIO::bilerp), reading the finer level's texels that the block samples: texels outside the
  // finer level are 0, as ImageCache::get_pixels gives (their weight is then exactly 0: only a
  // 1-texel-wide level samples past its edge).
  const int upW = width(level - 1), upH = height(level - 1);
  const Taps xs(x0, w, width(level), upW), ys(y0, h, height(level), upH);
  const int sx0 = xs.low.front(), sy0 = ys.low.front();
  const int sw = xs.low.back() + 2 - sx0, sh = ys.low.back() + 2 - sy0;
  const size_t srcStride = size_t(sw) * 3;
  const int ax = std::max(sx0, 0), bx = std::min(sx0 + sw, upW);
  // One buffer per level and thread, kept: the recursion through the finer levels uses one
  // each, and a tile's source is not allocated and paged in again per tile. (int sizes allow
  // 32 levels at most.)
  thread_local std::vector<float> buffers[32];
  std::vector<float>& buffer = buffers[level];
  auto bilerpRow = [&](int j, const float* r0, const float* r1) {
    float* o = out + size_t(j) * stride;
    const float yfrac = ys.frac[size_t(j)];
    if (xs.even) {
      // OIIO::bilerp's expression, t1 (v0 s1 + v1 s) + t (v2 s1 + v3 s) with s1 = 1 - s and
      // t1 = 1 - t, over consecutive texel pairs: the same operations, so the same floats. The
      // rows start at the first tap (sx0 = xs.low[0]).
      const float s = xs.frac[0], s1 = 1.0f - s, t = yfrac, t1 = 1.0f - t;
      const float *a = r0, *b = r1;
      for (int i = 0; i < w; ++i, a += 6, b += 6, o += 3)
        for (int c = 0; c < 3; ++c)
          o[c] = t1 * (a[c] * s1 + a[c + 3] * s) + t * (b[c] * s1 + b[c + 3] * s);
      return;
    }
    for (int i = 0; i < w; ++i) {
      const size_t x = 3 * size_t(xs.low[size_t(i)] - sx0);
      OIIO::bilerp(r0 + x, r0 + x + 3, r1 + x, r1 + x + 3, xs.frac[size_t(i)], yfrac, 3,
                   o + 3 * size_t(i));
    }
  };
  if (level - 1 == 0 || levels_[size_t(level - 1)].stored || fromTiles) {
    // The finer level's rows are cheap to read: two at a time, kept in the first cache level.
    if (buffer.size() < 2 * srcStride) buffer.resize(2 * srcStride);
    float* rows[2] = {buffer.data(), buffer.data() + srcStride};
    int rowY[2] = {INT_MIN, INT_MIN};
    auto sourceRow = [&](int y) -> const float* {
      for (int k = 0; k < 2; ++k)
        if (rowY[k] == y) return rows[k];
      const int k = rowY[0] == y - 1 ? 1 : 0;  // keep the row above
      const bool inside = y >= 0 && y < upH && ax < bx;
      if (inside)
        readBlock(level - 1, ax, y, bx - ax, 1, rows[k] + 3 * size_t(ax - sx0), srcStride,
                  fromTiles);
      zeroOutside(rows[k], sw, 1, ax - sx0, bx - sx0, inside ? 0 : 1, 1);
      rowY[k] = y;
      return rows[k];
    };
    for (int j = 0; j < h; ++j) {
      const float* r0 = sourceRow(ys.low[size_t(j)]);
      bilerpRow(j, r0, sourceRow(ys.low[size_t(j)] + 1));
    }
    return;
  }
  // The finer level is computed itself: as one block, so that no texel of it is made twice.
  if (buffer.size() < srcStride * size_t(sh)) buffer.resize(srcStride * size_t(sh));
  float* src = buffer.data();
  const int ay = std::max(sy0, 0), by = std::min(sy0 + sh, upH);
  if (ax < bx && ay < by)
    readBlock(level - 1, ax, ay, bx - ax, by - ay,
              src + size_t(ay - sy0) * srcStride + 3 * size_t(ax - sx0), srcStride, false);
  zeroOutside(src, sw, sh, ax - sx0, bx - sx0, ay - sy0, by - sy0);
  for (int j = 0; j < h; ++j) {
    const float* r0 = src + size_t(ys.low[size_t(j)] - sy0) * srcStride;
    bilerpRow(j, r0, r0 + srcStride);
  }
}

const float* TexturePyramid::makeTile(int level, int tx, int ty) const {
  // computeBlock over the tile, reading the finer level through its tiles (made in turn when
  // missing) or, for level 1, from the codes.
  const Level& l = levels_[size_t(level)];
  const int x0 = tx * kTile, y0 = ty * kTile;
  const int tw = std::min(kTile, l.width - x0), th = std::min(kTile, l.height - y0);
  // Not zero-filled (computeBlock writes every texel): 48 kB of memset per tile.
  auto texels = std::make_unique_for_overwrite<float[]>(size_t(tw) * size_t(th) * 3);
  computeBlock(level, x0, y0, tw, th, texels.get(), size_t(tw) * 3, true);
  std::atomic<const float*>& slot = l.tiles[size_t(ty) * size_t(l.tilesX) + size_t(tx)];
  const float* expected = nullptr;
  if (slot.compare_exchange_strong(expected, texels.get(), std::memory_order_acq_rel)) {
    tilesMade_.fetch_add(1, std::memory_order_relaxed);
    tileBytes_.fetch_add(uint64_t(tw) * uint64_t(th) * 3 * sizeof(float),
                         std::memory_order_relaxed);
    return texels.release();
  }
  return expected;  // another thread published the same tile first; ours is dropped
}

uint64_t TexturePyramid::storedBytes() const {
  uint64_t n = 0;
  for (const Level& l : levels_) n += l.storedTexels.size() * sizeof(float);
  return n;
}

uint64_t TexturePyramid::tileBytesAtMost(int width, int height) {
  uint64_t n = 0;
  for (int level = 1; level <= kComputed && (width > 1 || height > 1); ++level) {
    width = std::max(1, width / 2);
    height = std::max(1, height / 2);
    n += uint64_t(width) * uint64_t(height) * 3 * sizeof(float);
  }
  return n;
}

}  // namespace tray
