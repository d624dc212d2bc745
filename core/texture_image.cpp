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

namespace {

/// Codes of kChannels (grey replicated) through `table`: n texels from texel index `first` on,
/// as RGB floats. Specialised per channel count and code width: MIP tiles read level 0 this
/// way (textures/texture_pyramid.cpp), and a loop that asks both per texel costs them twice.
template <bool kWide, int kChannels>
void decodeCodes(const unsigned char* bytes, const float* table, size_t first, int n, float* out) {
  constexpr size_t g = kChannels >= 3 ? 1 : 0;
  for (int i = 0; i < n; ++i, out += 3) {
    const size_t k = (first + size_t(i)) * kChannels;
    if constexpr (kWide) {
      uint16_t v[3];
      __builtin_memcpy(&v[0], bytes + 2 * k, 2);
      __builtin_memcpy(&v[1], bytes + 2 * (k + g), 2);
      __builtin_memcpy(&v[2], bytes + 2 * (k + 2 * g), 2);
      out[0] = table[v[0]], out[1] = table[v[1]], out[2] = table[v[2]];
    } else {
      out[0] = table[bytes[k]], out[1] = table[bytes[k + g]], out[2] = table[bytes[k + 2 * g]];
    }
  }
}

template <bool kWide>
void decodeCodes(int channels, const unsigned char* bytes, const float* table, size_t first, int n,
                 float* out) {
  switch (channels) {
    case 1:
      return decodeCodes<kWide, 1>(bytes, table, first, n, out);
    case 2:
      return decodeCodes<kWide, 2>(bytes, table, first, n, out);
    case 3:
      return decodeCodes<kWide, 3>(bytes, table, first, n, out);
    default:
      return decodeCodes<kWide, 4>(bytes, table, first, n, out);
  }
}

}  // namespace

void TextureImage::texels(size_t first, int count, float* rgb) const {
  if (!codes) {
    std::memcpy(rgb, pixels.data() + 3 * first, size_t(count) * 3 * sizeof(float));
    return;
  }
  const unsigned char* bytes = codes->bytes.data();
  if (codes->wide)
    decodeCodes<true>(codes->channels, bytes, table->data(), first, count, rgb);
  else
    decodeCodes<false>(codes->channels, bytes, table->data(), first, count, rgb);
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
