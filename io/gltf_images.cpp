#include "io/gltf_images.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstring>

namespace tray {

namespace {

/// The format a file's first bytes announce: "png", "jpeg" or "" (anything else). The bytes,
/// not the name or the stated mimeType, choose OIIO's reader.
const char* formatOf(const unsigned char* b, size_t n) {
  static const unsigned char kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (n >= 8 && std::memcmp(b, kPng, 8) == 0) return "png";
  if (n >= 3 && b[0] == 0xff && b[1] == 0xd8 && b[2] == 0xff) return "jpeg";
  return "";
}

std::string imageName(const tinygltf::Image& im, int index) {
  std::string s = nameOf("image", index, im.name);
  if (!im.uri.empty() && im.uri.rfind("data:", 0) != 0) s += " ('" + im.uri + "')";
  return s;
}

}  // namespace

float srgbToLinear(float c) {
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

bool ImageBytes::record(tinygltf::Image* image, int index, std::string*, std::string*, int, int,
                        const unsigned char* bytes, int size, void* self) {
  auto* out = static_cast<ImageBytes*>(self);
  if (index < 0 || image->bufferView != -1 || size <= 0) return true;
  if (out->byImage.size() <= size_t(index)) out->byImage.resize(size_t(index) + 1);
  out->byImage[size_t(index)].assign(bytes, bytes + size);
  return true;
}

TextureImage decodeImage(const GltfContext& ctx, const ImageBytes& bytes, int index, bool srgb,
                         uint64_t& pixelBudget) {
  const tinygltf::Image& im = ctx.model.images[size_t(index)];
  const std::string where = imageName(im, index);
  const unsigned char* data = nullptr;
  size_t size = 0;
  if (im.bufferView >= 0) {
    // gltf_validate checked that the bufferView lies inside its buffer.
    const auto& bv = ctx.model.bufferViews[size_t(im.bufferView)];
    data = ctx.model.buffers[size_t(bv.buffer)].data.data() + bv.byteOffset;
    size = bv.byteLength;
  } else if (size_t(index) < bytes.byImage.size()) {
    data = bytes.byImage[size_t(index)].data();
    size = bytes.byImage[size_t(index)].size();
  }
  if (!data || size == 0) ctx.fail(where + ": no image data (missing file or empty data: URI)");
  const char* format = formatOf(data, size);
  if (!*format) ctx.fail(where + ": not a PNG or JPEG image (the only formats glTF 2.0 allows)");

  // Never let OIIO guess a reader from content: only the one the signature chose may run.
  OIIO::attribute("try_all_readers", 0);
  OIIO::Filesystem::IOMemReader memory(data, size);
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);  // glTF colours are not premultiplied
  auto in = OIIO::ImageInput::create(format, false, &config);
  OIIO::ImageSpec spec;
  if (!in || !in->set_ioproxy(&memory) || !in->open(where, spec, config))
    ctx.fail(where + ": cannot decode " + format + ": " + (in ? in->geterror() : OIIO::geterror()));
  const uint64_t pixels = uint64_t(std::max(spec.width, 0)) * uint64_t(std::max(spec.height, 0));
  if (spec.width <= 0 || spec.height <= 0 || spec.depth != 1 || spec.nchannels < 1)
    ctx.fail(where + ": the " + format + " header states no pixels");
  if (pixels > kMaxTexturePixels)
    ctx.fail(where + ": " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
             " pixels exceeds the limit of " + std::to_string(kMaxTexturePixels) +
             " pixels per texture");
  if (pixels > pixelBudget)
    ctx.fail(where + ": the scene's textures exceed the limit of " +
             std::to_string(kMaxSceneTexturePixels) + " pixels in all");
  pixelBudget -= pixels;

  const int nc = spec.nchannels;
  std::vector<float> raw(pixels * size_t(nc));
  if (!in->read_image(0, 0, 0, nc, OIIO::TypeDesc::FLOAT, raw.data()))
    ctx.fail(where + ": cannot decode " + format + ": " + in->geterror());
  in->close();

  TextureImage out;
  out.name = where;
  out.width = spec.width;
  out.height = spec.height;
  out.srgb = srgb;
  out.pixels.resize(pixels * 3);
  // Grey (and grey + alpha) fills all three channels; alpha is not used (opaque rendering).
  for (size_t p = 0; p < pixels; ++p)
    for (int c = 0; c < 3; ++c) {
      float v = raw[p * size_t(nc) + size_t(nc >= 3 ? c : 0)];
      out.pixels[3 * p + size_t(c)] = srgb ? srgbToLinear(v) : v;
    }
  return out;
}

}  // namespace tray
