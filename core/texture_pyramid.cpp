#include "core/texture_pyramid.h"

#include <OpenImageIO/fmath.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstring>

namespace tray {

TexturePyramid::TexturePyramid(const TextureImage& image) : image_(image) {
  int w = image.width, h = image.height;
  width_.push_back(w);
  height_.push_back(h);
  while (w > 1 || h > 1) {  // ImageCacheFile::open, automip
    w = std::max(1, w / 2);
    h = std::max(1, h / 2);
    width_.push_back(w);
    height_.push_back(h);
  }
  stored_.resize(width_.size());
  for (int level = kComputed + 1; level < levels(); ++level) {
    const size_t rowFloats = size_t(width(level)) * 3;
    std::vector<float> texels(rowFloats * size_t(height(level)));
    tbb::parallel_for(0, height(level), [&](int y) {
      compute(level, y, texels.data() + size_t(y) * rowFloats);
    });
    stored_[size_t(level)] = std::move(texels);
  }
}

void TexturePyramid::row(int level, int y, float* rgb) const {
  if (level == 0) return image_.row(y, rgb);
  const auto& stored = stored_[size_t(level)];
  if (stored.empty()) return compute(level, y, rgb);
  const size_t n = size_t(width(level)) * 3;
  std::memcpy(rgb, stored.data() + size_t(y) * n, n * sizeof(float));
}

void TexturePyramid::compute(int level, int y, float* rgb) const {
  // OIIO's read_unmipped, texel by texel, with the same float expressions: the texel centre
  // (j + 0.5) / height in the level's [0, 1], scaled to the finer level, minus half a texel.
  const int upW = width(level - 1), upH = height(level - 1), w = width(level);
  const float yf = (y + 0.5f) / float(height(level));
  int ylow;
  const float yfrac = OIIO::floorfrac(yf * upH - 0.5, &ylow);
  // The two finer rows; texels outside the finer level are 0, as ImageCache::get_pixels gives
  // (their weight is then exactly 0: only a 1-texel-wide level samples past its edge).
  std::vector<float> rows(size_t(upW) * 6, 0.0f);
  float* r0 = rows.data();
  float* r1 = rows.data() + size_t(upW) * 3;
  if (ylow >= 0 && ylow < upH) row(level - 1, ylow, r0);
  if (ylow + 1 >= 0 && ylow + 1 < upH) row(level - 1, ylow + 1, r1);
  static const float kZero[3] = {0, 0, 0};
  auto at = [&](const float* r, int x) { return x >= 0 && x < upW ? r + 3 * size_t(x) : kZero; };
  for (int i = 0; i < w; ++i) {
    const float xf = (i + 0.5f) / float(w);
    int xlow;
    const float xfrac = OIIO::floorfrac(xf * upW - 0.5, &xlow);
    OIIO::bilerp(at(r0, xlow), at(r0, xlow + 1), at(r1, xlow), at(r1, xlow + 1), xfrac, yfrac, 3,
                 rgb + 3 * size_t(i));
  }
}

uint64_t TexturePyramid::storedBytes() const {
  uint64_t n = 0;
  for (const auto& s : stored_) n += s.size() * sizeof(float);
  return n;
}

}  // namespace tray
