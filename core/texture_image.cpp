#include "core/texture_image.h"

#include <cstring>

namespace tray {

bool TextureImage::valid() const {
  if (width <= 0 || height <= 0) return false;
  const size_t n = size_t(width) * size_t(height);
  if (!codes) return pixels.size() == n * 3;
  const size_t levels = codes->wide ? 65536 : 256;
  return codes->channels >= 1 && table && table->size() == levels &&
         codes->bytes.size() == n * size_t(codes->channels) * (codes->wide ? 2 : 1);
}

void TextureImage::row(int y, float* rgb) const {
  const size_t w = size_t(width);
  if (!codes) {
    std::memcpy(rgb, pixels.data() + size_t(y) * w * 3, w * 3 * sizeof(float));
    return;
  }
  const float* t = table->data();
  const size_t nc = size_t(codes->channels);
  const size_t first = size_t(y) * w * nc;
  for (size_t x = 0; x < w; ++x)
    for (size_t c = 0; c < 3; ++c)
      rgb[3 * x + c] = t[codes->code(first + x * nc + (nc >= 3 ? c : 0))];
}

float TextureImage::alphaAt(size_t p) const {
  if (!alpha.empty()) return alpha[p];
  if (!codesAlpha) return 1.0f;
  // As the loader computed it: code / (levels - 1), PNG alpha being linear.
  const float scale = 1.0f / float(codes->wide ? 65535 : 255);
  const size_t nc = size_t(codes->channels);
  return float(codes->code(p * nc + nc - 1)) * scale;
}

uint64_t TextureImage::bytes() const {
  return codes ? codes->bytes.size() : (pixels.size() + alpha.size()) * sizeof(float);
}

}  // namespace tray
