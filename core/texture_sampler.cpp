#include "core/texture_sampler.h"

#include <OpenImageIO/imagecache.h>
#include <OpenImageIO/imageio.h>
#include <OpenImageIO/texture.h>

#include <cstring>
#include <string>

#include "core/error.h"

namespace tray {

namespace {

using OIIO::TextureOpt;

/// Serves one TextureImage to OIIO's ImageCache as a float RGB scanline image. The image
/// arrives as a pointer in the open() configuration (ImageCache::add_file passes it through),
/// since an ImageInput::Creator is a plain function without state.
class MemoryTextureInput final : public OIIO::ImageInput {
 public:
  static constexpr const char* kImageAttribute = "tray:textureImage";
  static OIIO::ImageInput* create() { return new MemoryTextureInput; }

  const char* format_name() const override { return "tray-memory"; }
  bool open(const std::string&, OIIO::ImageSpec&) override { return false; }
  bool open(const std::string&, OIIO::ImageSpec& spec, const OIIO::ImageSpec& config) override {
    void* ptr = nullptr;
    config.getattribute(kImageAttribute, OIIO::TypeDesc::PTR, &ptr);
    image_ = static_cast<const TextureImage*>(ptr);
    if (!image_ || image_->width <= 0 || image_->height <= 0) return false;
    m_spec = OIIO::ImageSpec(image_->width, image_->height, 3, OIIO::TypeDesc::FLOAT);
    spec = m_spec;
    return true;
  }
  bool close() override { return true; }
  bool read_native_scanline(int subimage, int miplevel, int y, int, void* data) override {
    if (subimage != 0 || miplevel != 0 || y < 0 || y >= image_->height) return false;
    const size_t row = size_t(image_->width) * 3;
    std::memcpy(data, image_->pixels.data() + size_t(y) * row, row * sizeof(float));
    return true;
  }

 private:
  const TextureImage* image_ = nullptr;
};

TextureOpt::Wrap wrapOf(TextureWrap w) {
  switch (w) {
    case TextureWrap::kClampToEdge:
      return TextureOpt::WrapClamp;
    case TextureWrap::kMirroredRepeat:
      return TextureOpt::WrapMirror;
    case TextureWrap::kRepeat:
      break;
  }
  return TextureOpt::WrapPeriodic;
}

/// The glTF filter as OIIO's texel interpolation and MIP mode.
void filterOf(TextureFilter f, TextureOpt& opt) {
  using F = TextureFilter;
  const bool nearestTexel =
      f == F::kNearest || f == F::kNearestMipmapNearest || f == F::kNearestMipmapLinear;
  opt.interpmode = nearestTexel ? TextureOpt::InterpClosest : TextureOpt::InterpBilinear;
  switch (f) {
    case F::kNearest:
    case F::kLinear:
      opt.mipmode = TextureOpt::MipModeNoMIP;
      break;
    case F::kNearestMipmapNearest:
    case F::kLinearMipmapNearest:
      opt.mipmode = TextureOpt::MipModeOneLevel;
      break;
    case F::kNearestMipmapLinear:
    case F::kLinearMipmapLinear:
      opt.mipmode = TextureOpt::MipModeTrilinear;
      break;
  }
}

}  // namespace

Vec2 transformUv(const TextureRef& ref, Vec2 uv, bool vector) {
  // Rows of R: (cos, sin), (-sin, cos) -- the README's example (offset [0, 1], rotation pi/2,
  // scale 0.5 selects the lower-left quadrant) fixes this sign.
  const bool turned = ref.rotation != 0;
  const float c = turned ? std::cos(ref.rotation) : 1.0f,
              s = turned ? std::sin(ref.rotation) : 0.0f;
  const float su = ref.scaleUV.x * uv.x, sv = ref.scaleUV.y * uv.y;
  Vec2 out{c * su + s * sv, -s * su + c * sv};
  if (!vector) out.x += ref.offset.x, out.y += ref.offset.y;
  return out;
}

struct TextureSampler::Impl {
  OIIO::TextureSystem* ts = nullptr;
  std::vector<OIIO::TextureSystem::TextureHandle*> handles;
  const std::vector<TextureImage>& images;
  explicit Impl(const std::vector<TextureImage>& im) : images(im) {}
};

TextureSampler::TextureSampler(const std::vector<TextureImage>& images)
    : impl_(std::make_unique<Impl>(images)) {
  // A private TextureSystem (shared = false): its cache settings are TRay's alone.
  OIIO::TextureSystem* ts = OIIO::TextureSystem::create(false);
  impl_->ts = ts;
  double bytes = 0;
  for (const auto& im : images) bytes += double(im.pixels.size()) * sizeof(float);
  // automip: OIIO builds the MIP pyramid of each (untiled, single-level) image itself; the
  // cache may hold every level of every image (4/3 of the pixels) plus slack.
  ts->attribute("automip", 1);
  ts->attribute("autotile", 64);
  ts->attribute("deduplicate", 0);
  ts->attribute("max_memory_MB", float(std::max(256.0, bytes * 1.5 / (1 << 20) + 64)));
  OIIO::ImageCache* cache = ts->imagecache();
  for (size_t i = 0; i < images.size(); ++i) {
    const TextureImage& im = images[i];
    if (im.width <= 0 || im.height <= 0 ||
        im.pixels.size() != size_t(im.width) * size_t(im.height) * 3)
      throw Error("texture '" + im.name + "' has no pixels or a wrong pixel count");
    OIIO::ImageSpec config;
    const void* ptr = &im;
    config.attribute(MemoryTextureInput::kImageAttribute, OIIO::TypeDesc::PTR, &ptr);
    OIIO::ustring name("tray:texture/" + std::to_string(i));
    if (!cache->add_file(name, &MemoryTextureInput::create, &config))
      throw Error("texture '" + im.name + "': OpenImageIO: " + cache->geterror());
    impl_->handles.push_back(ts->get_texture_handle(name));
  }
}

TextureSampler::~TextureSampler() {
  OIIO::TextureSystem::destroy(impl_->ts);
}

Color TextureSampler::sample(const TextureRef& ref, const UvFootprint& f) const {
  if (ref.image < 0 || size_t(ref.image) >= impl_->handles.size()) return Color(1.0f);
  const TextureImage& im = impl_->images[size_t(ref.image)];
  const Vec2 uv = transformUv(ref, f.uv);
  const Vec2 dx = transformUv(ref, f.dx, true), dy = transformUv(ref, f.dy, true);
  TextureOpt opt;
  opt.swrap = wrapOf(ref.wrapS);
  opt.twrap = wrapOf(ref.wrapT);
  // Footprint in texels of the finest level: under one texel the texture is magnified.
  const float w = float(im.width), h = float(im.height);
  const float texels = std::max(std::hypot(dx.x * w, dx.y * h), std::hypot(dy.x * w, dy.y * h));
  filterOf(texels > 1.0f ? ref.minFilter : ref.magFilter, opt);
  float rgb[3] = {0, 0, 0};
  auto* perThread = impl_->ts->get_perthread_info();
  // OIIO's t runs down the image from its first row, as glTF's v does (glTF 2.0 §3.8.4.1).
  if (!impl_->ts->texture(impl_->handles[size_t(ref.image)], perThread, opt, uv.x, uv.y, dx.x, dx.y,
                          dy.x, dy.y, 3, rgb))
    return Color(1.0f);  // cannot happen for images registered above; shade untextured
  return {rgb[0], rgb[1], rgb[2]};
}

}  // namespace tray
