#include "gltf/gltf_images.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstring>
#include <memory>

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

namespace {

/// Opens the reader the signature chose on the in-memory bytes (the proxy must outlive it).
std::unique_ptr<OIIO::ImageInput> openImage(const GltfContext& ctx, const ImageInfo& info,
                                            OIIO::Filesystem::IOMemReader& memory,
                                            OIIO::ImageSpec& spec) {
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);  // glTF colours are not premultiplied
  auto in = OIIO::ImageInput::create(info.format, false, &config);
  if (!in || !in->set_ioproxy(&memory) || !in->open(info.where, spec, config))
    ctx.fail(info.where + ": cannot decode " + info.format + ": " +
             (in ? in->geterror() : OIIO::geterror()));
  return in;
}

}  // namespace

ImageInfo inspectImage(const GltfContext& ctx, const ImageBytes& bytes, int index) {
  const tinygltf::Image& im = ctx.model.images[size_t(index)];
  ImageInfo info;
  info.index = index;
  info.where = imageName(im, index);
  if (im.bufferView >= 0) {
    // gltf_validate checked that the bufferView lies inside its buffer.
    const auto& bv = ctx.model.bufferViews[size_t(im.bufferView)];
    info.data = ctx.model.buffers[size_t(bv.buffer)].data.data() + bv.byteOffset;
    info.size = bv.byteLength;
  } else if (size_t(index) < bytes.byImage.size()) {
    info.data = bytes.byImage[size_t(index)].data();
    info.size = bytes.byImage[size_t(index)].size();
  }
  if (!info.data || info.size == 0)
    ctx.fail(info.where + ": no image data (missing file or empty data: URI)");
  info.format = formatOf(info.data, info.size);
  if (!*info.format)
    ctx.fail(info.where + ": not a PNG or JPEG image (the only formats glTF 2.0 allows)");
  // Never let OIIO guess a reader from content: only the one the signature chose may run.
  OIIO::attribute("try_all_readers", 0);
  OIIO::Filesystem::IOMemReader memory(info.data, info.size);
  OIIO::ImageSpec spec;
  openImage(ctx, info, memory, spec);
  if (spec.width <= 0 || spec.height <= 0 || spec.depth != 1 || spec.nchannels < 1)
    ctx.fail(info.where + ": the " + info.format + " header states no pixels");
  info.width = spec.width;
  info.height = spec.height;
  info.channels = spec.nchannels;
  info.wide = spec.format.size() > 1;
  if (info.pixels() > kMaxTexturePixels)
    ctx.fail(info.where + ": " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
             " pixels exceeds the limit of " + std::to_string(kMaxTexturePixels) +
             " pixels per texture");
  return info;
}

void decodeImage(const GltfContext& ctx, const ImageInfo& info, bool srgb, bool linear,
                 TextureImage out[2], bool alpha) {
  OIIO::Filesystem::IOMemReader memory(info.data, info.size);
  OIIO::ImageSpec spec;
  auto in = openImage(ctx, info, memory, spec);
  if (spec.width != info.width || spec.height != info.height)
    ctx.fail(info.where + ": the image header changed between reads");
  const size_t pixels = size_t(info.pixels());
  // Keep the file's own 8- or 16-bit codes, shared by both views (decoded once); each view
  // maps them to linear floats through a table, one pow per code value instead of one per
  // texel, when the texture filter reads a texel (TexturePyramid::texel) or a row.
  const int nc = spec.nchannels;
  const bool wide = spec.format.size() > 1;
  const OIIO::TypeDesc type = wide ? OIIO::TypeDesc::UINT16 : OIIO::TypeDesc::UINT8;
  auto codes = std::make_shared<TexelCodes>();
  codes->channels = nc;
  codes->wide = wide;
  codes->bytes.resize(pixels * size_t(nc) * type.size());
  if (!in->read_image(0, 0, 0, nc, type, codes->bytes.data()))
    ctx.fail(info.where + ": cannot decode " + info.format + ": " + in->geterror());
  in->close();
  const size_t levels = wide ? 65536 : 256;
  for (int e = 0; e < 2; ++e) {
    if (!(e == 0 ? srgb : linear)) continue;
    auto table = std::make_shared<std::vector<float>>(levels);
    for (size_t i = 0; i < levels; ++i) {
      const float v = float(i) / float(levels - 1);
      (*table)[i] = e == 0 ? srgbToLinear(v) : v;
    }
    TextureImage& t = out[e];
    t.name = info.where;
    t.width = info.width;
    t.height = info.height;
    t.srgb = e == 0;
    t.codes = codes;
    t.table = std::move(table);
    // Alpha (the last of 2 or 4 channels) is linear in PNG whatever the colour encoding.
    t.codesAlpha = e == 0 && alpha && (nc == 2 || nc == 4);
  }
}

}  // namespace tray
