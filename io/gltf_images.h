#pragma once
// glTF images (glTF 2.0 §3.8.3) decoded into TextureImages through OpenImageIO, after the
// document has been validated. Only PNG and JPEG, the formats glTF 2.0 allows, are opened.
#include <cstdint>
#include <vector>

#include "core/scene.h"
#include "io/gltf_context.h"

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

/// Decodes glTF image `index` to linear float RGB (sRGB EOTF applied if `srgb`). Throws the
/// one-line "PATH: image N 'uri': problem" for a missing, non-PNG/JPEG, corrupt or too large
/// image. `pixelBudget` is what remains of kMaxSceneTexturePixels and is reduced.
TextureImage decodeImage(const GltfContext& ctx, const ImageBytes& bytes, int index, bool srgb,
                         uint64_t& pixelBudget);

/// The exact sRGB EOTF (IEC 61966-2-1): encoded [0, 1] -> linear.
float srgbToLinear(float encoded);

}  // namespace tray
