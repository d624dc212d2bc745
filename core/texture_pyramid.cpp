#include "core/texture_pyramid.h"

#include <OpenImageIO/fmath.h>
#include <tbb/parallel_for.h>

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

const float kZero[3] = {0, 0, 0};

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
    const size_t rowFloats = size_t(l.width) * 3;
    std::vector<float> texels(rowFloats * size_t(l.height));
    tbb::parallel_for(0, l.height, [&](int y) {
      compute(level, y, texels.data() + size_t(y) * rowFloats);
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
  if (!l.stored) return compute(level, y, rgb);
  const size_t n = size_t(l.width) * 3;
  std::memcpy(rgb, l.stored + size_t(y) * n, n * sizeof(float));
}

void TexturePyramid::compute(int level, int y, float* rgb) const {
  // OIIO's read_unmipped, texel by texel, with the same float expressions (sourceTexel).
  const int upW = width(level - 1), upH = height(level - 1), w = width(level);
  int ylow;
  const float yfrac = sourceTexel(y, height(level), upH, &ylow);
  // The two finer rows; texels outside the finer level are 0, as ImageCache::get_pixels gives
  // (their weight is then exactly 0: only a 1-texel-wide level samples past its edge).
  std::vector<float> rows(size_t(upW) * 6, 0.0f);
  float* r0 = rows.data();
  float* r1 = rows.data() + size_t(upW) * 3;
  if (ylow >= 0 && ylow < upH) row(level - 1, ylow, r0);
  if (ylow + 1 >= 0 && ylow + 1 < upH) row(level - 1, ylow + 1, r1);
  auto at = [&](const float* r, int x) { return x >= 0 && x < upW ? r + 3 * size_t(x) : kZero; };
  for (int i = 0; i < w; ++i) {
    int xlow;
    const float xfrac = sourceTexel(i, w, upW, &xlow);
    OIIO::bilerp(at(r0, xlow), at(r0, xlow + 1), at(r1, xlow), at(r1, xlow + 1), xfrac, yfrac, 3,
                 rgb + 3 * size_t(i));
  }
}

const float* TexturePyramid::makeTile(int level, int tx, int ty) const {
  // compute()'s arithmetic, texel by texel, reading the finer level through texel() (which
  // makes its tiles in turn when they are missing).
  const Level& l = levels_[size_t(level)];
  const int upW = width(level - 1), upH = height(level - 1);
  const int x0 = tx * kTile, y0 = ty * kTile;
  const int tw = std::min(kTile, l.width - x0), th = std::min(kTile, l.height - y0);
  auto texels = std::make_unique<float[]>(size_t(tw) * size_t(th) * 3);
  float scratch[4][3];
  auto at = [&](int x, int y, int k) {
    return x >= 0 && x < upW && y >= 0 && y < upH ? texel(level - 1, x, y, scratch[k]) : kZero;
  };
  int xlow[kTile];
  float xfrac[kTile];
  for (int i = 0; i < tw; ++i) xfrac[i] = sourceTexel(x0 + i, l.width, upW, &xlow[i]);
  for (int j = 0; j < th; ++j) {
    int ylow;
    const float yfrac = sourceTexel(y0 + j, l.height, upH, &ylow);
    for (int i = 0; i < tw; ++i) {
      const int x = xlow[i];
      OIIO::bilerp(at(x, ylow, 0), at(x + 1, ylow, 1), at(x, ylow + 1, 2), at(x + 1, ylow + 1, 3),
                   xfrac[i], yfrac, 3, texels.get() + 3 * (size_t(j) * size_t(tw) + size_t(i)));
    }
  }
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
