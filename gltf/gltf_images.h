#pragma once
// glTF images (glTF 2.0 §3.8.3) decoded into TextureImages through OpenImageIO, after the
// document has been validated. Only PNG and JPEG, the formats glTF 2.0 allows, are opened.
#include <cstdint>
#include <string>
#include <vector>

#include "core/scene.h"
#include "gltf/gltf_context.h"

namespace tray {

/// Largest texture TRay decodes: 8192 x 8192 pixels (768 MiB as float RGB); and the sum over
/// a scene. Checked from the image header, before any pixel is decoded.
constexpr uint64_t kMaxTexturePixels = uint64_t(8192) * 8192;
constexpr uint64_t kMaxSceneTexturePixels = 4 * kMaxTexturePixels;

/// The encoded bytes of images given by URI (data: or a file, read through the loader's
/// FileAccess), recorded by tinygltf's image callback; bufferView images are read from their
/// (validated) bufferView instead, never through the callback's unchecked pointer.
struct ImageBytes {
  std::vector<std::vector<unsigned char>> byImage;  ///< indexed by glTF image; may be empty

  /// tinygltf LoadImageDataFunction; user data: ImageBytes*.
  static bool record(tinygltf::Image* image, int index, std::string* err, std::string* warn,
                     int reqWidth, int reqHeight, const unsigned char* bytes, int size, void* self);
};

/// What an image's header says, checked: where its bytes are, its format and size.
struct ImageInfo {
  int index = -1;
  std::string where;  ///< "image 2 ('wood.png')" for messages
  const unsigned char* data = nullptr;
  size_t size = 0;
  const char* format = "";  ///< "png" or "jpeg"
  int width = 0, height = 0;
  int channels = 0;   ///< as stored (1 to 4)
  bool wide = false;  ///< 16-bit codes
  uint64_t pixels() const { return uint64_t(width) * uint64_t(height); }
  /// What decodeImage keeps: the file's codes, shared by the sRGB and the linear view.
  uint64_t codeBytes() const { return pixels() * uint64_t(channels) * (wide ? 2 : 1); }
};

/// Finds glTF image `index`'s bytes and reads its header. Throws the one-line "PATH: image N
/// 'uri': problem" for a missing, non-PNG/JPEG or corrupt image, or one over kMaxTexturePixels.
ImageInfo inspectImage(const GltfContext& ctx, const ImageBytes& bytes, int index);

/// Decodes an inspected image to linear float RGB: out[0] sRGB-decoded (the sRGB EOTF applied)
/// if `srgb`, out[1] as stored if `linear` (entries not asked for stay empty). `alpha`: out[0]
/// also keeps the file's alpha channel, linear (for alpha-tested base colours). Thread-safe.
void decodeImage(const GltfContext& ctx, const ImageInfo& info, bool srgb, bool linear,
                 TextureImage out[2], bool alpha = false);

/// The exact sRGB EOTF (IEC 61966-2-1): encoded [0, 1] -> linear.
float srgbToLinear(float encoded);

}  // namespace tray
