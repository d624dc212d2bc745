#pragma once
// A decoded texture image as TRay keeps it in memory: either linear float RGB (tests, small
// images built in code) or, as the glTF loader stores it, the file's own 8- or 16-bit codes
// with a table from code to linear float. The codes are shared by the sRGB and the linear
// view of one image (decoded once); the texture filter reads them texel by texel through the
// table (textures/texture_pyramid.h), OIIO's paged fallback as float rows made on demand, so an
// 8192 x 8192 RGB PNG costs 192 MiB here instead of 768 MiB of floats per view
// (docs/textures.md, "Memory").
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace tray {

/// Texels as the file stored them: `channels` (1 grey, 2 grey + alpha, 3 RGB, 4 RGBA) codes of
/// 8 bits, or of 16 bits in native byte order when `wide`.
struct TexelCodes {
  int channels = 3;
  bool wide = false;
  std::vector<unsigned char> bytes;  ///< width * height * channels * (wide ? 2 : 1)

  uint32_t code(size_t k) const {
    if (!wide) return bytes[k];
    uint16_t v;
    __builtin_memcpy(&v, &bytes[2 * k], 2);
    return v;
  }
};

/// A decoded texture image: linear float RGB, row 0 at the top (glTF's uv origin), filled by
/// the texture loader (io/gltf_images) or by tests. Colour textures are linearised from sRGB
/// when decoded (through `table`), so that filtering happens on linear values.
struct TextureImage {
  std::string name;  ///< for messages: the file's path, or "image N" for embedded images
  int width = 0, height = 0;
  std::vector<float> pixels;  ///< width * height * 3; empty when `codes` holds the texels
  std::vector<float> alpha;   ///< width * height, linear; empty = opaque, or in `codes`
  bool srgb = false;          ///< the file's values were sRGB-decoded
  /// Compact texels (shared between the views of one image) and this view's table from code
  /// to linear float (256 or 65536 entries).
  std::shared_ptr<const TexelCodes> codes;
  std::shared_ptr<const std::vector<float>> table;
  bool codesAlpha = false;  ///< alpha is the codes' last channel (2 or 4 channels), linear

  /// Width and height positive and the texels (floats or codes + table) of that size.
  bool valid() const;
  /// Row y as width * 3 linear floats: for codes, table[code] (grey fills all three channels),
  /// exactly the floats the loader stored in `pixels` before codes existed.
  void row(int y, float* rgb) const { texels(size_t(y) * size_t(width), width, rgb); }
  /// `count` texels from row-major texel index `first` on (within one row or across rows),
  /// as row() gives them, into rgb[0 .. 3 count).
  void texels(size_t first, int count, float* rgb) const;
  bool hasAlpha() const { return !alpha.empty() || codesAlpha; }
  /// Linear alpha of pixel p (row-major); 1 when the image has none.
  float alphaAt(size_t p) const;
  /// Bytes of texels this view holds (codes counted in full for each view sharing them).
  uint64_t bytes() const;
};

}  // namespace tray
