#include "core/texture_sampler.h"

#include <OpenImageIO/imagecache.h>
#include <OpenImageIO/imageio.h>
#include <OpenImageIO/sysutil.h>
#include <OpenImageIO/texture.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "core/error.h"
#include "core/texture_pyramid.h"

namespace tray {

namespace {

using OIIO::TextureOpt;

/// Serves one TextureImage's MIP pyramid to OIIO's ImageCache as a float RGB scanline image with
/// one MIP level per pyramid level, made from the compact codes as OIIO asks for rows. The
/// pyramid arrives as a pointer in the open() configuration (ImageCache::add_file passes it
/// through), since an ImageInput::Creator is a plain function without state.
class MemoryTextureInput final : public OIIO::ImageInput {
 public:
  static constexpr const char* kImageAttribute = "tray:texturePyramid";
  static constexpr const char* kLevelsAttribute = "tray:levels";  ///< 1: level 0 only
  static OIIO::ImageInput* create() { return new MemoryTextureInput; }

  const char* format_name() const override { return "tray-memory"; }
  bool open(const std::string&, OIIO::ImageSpec&) override { return false; }
  bool open(const std::string&, OIIO::ImageSpec& spec, const OIIO::ImageSpec& config) override {
    void* ptr = nullptr;
    config.getattribute(kImageAttribute, OIIO::TypeDesc::PTR, &ptr);
    pyramid_ = static_cast<const TexturePyramid*>(ptr);
    levels_ = pyramid_ ? config.get_int_attribute(kLevelsAttribute, pyramid_->levels()) : 0;
    if (!pyramid_ || !seek_subimage(0, 0)) return false;
    spec = m_spec;
    return true;
  }
  bool close() override { return true; }
  int current_miplevel() const override { return level_; }
  bool seek_subimage(int subimage, int miplevel) override {
    if (subimage != 0 || miplevel < 0 || miplevel >= levels_) return false;
    level_ = miplevel;
    m_spec = OIIO::ImageSpec(pyramid_->width(miplevel), pyramid_->height(miplevel), 3,
                             OIIO::TypeDesc::FLOAT);
    return true;
  }
  bool read_native_scanline(int subimage, int miplevel, int y, int, void* data) override {
    if (subimage != 0 || miplevel < 0 || miplevel >= levels_ || y < 0 ||
        y >= pyramid_->height(miplevel))
      return false;
    pyramid_->row(miplevel, y, static_cast<float*>(data));
    return true;
  }

 private:
  const TexturePyramid* pyramid_ = nullptr;
  int levels_ = 0, level_ = 0;
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
  std::vector<std::unique_ptr<TexturePyramid>> pyramids;
  const std::vector<TextureImage>& images;
  explicit Impl(const std::vector<TextureImage>& im) : images(im) {}
};

TextureSampler::TextureSampler(const std::vector<TextureImage>& images, double cacheMB,
                               bool oiioAutomip)
    : impl_(std::make_unique<Impl>(images)) {
  // A private TextureSystem (shared = false): its cache settings are TRay's alone.
  OIIO::TextureSystem* ts = OIIO::TextureSystem::create(false);
  impl_->ts = ts;
  // Each image arrives MIP-mapped (TexturePyramid, OIIO's own automip arithmetic), read in
  // 64-row strips (autotile); the cache holds tiles only, at most max_memory_MB. Which tiles
  // are resident never changes a texel's value, so the budget does not change pixels.
  // automip stays on for oiioAutomip (tests): OIIO then makes the levels itself.
  ts->attribute("automip", 1);
  ts->attribute("autotile", 64);
  ts->attribute("deduplicate", 0);
  ts->attribute("max_memory_MB", float(cacheMB > 0 ? cacheMB : budgetFor(images)));
  OIIO::ImageCache* cache = ts->imagecache();
  for (size_t i = 0; i < images.size(); ++i) {
    const TextureImage& im = images[i];
    if (!im.valid())
      throw Error("texture '" + im.name + "' has no pixels or a wrong pixel count");
    OIIO::ImageSpec config;
    impl_->pyramids.push_back(std::make_unique<TexturePyramid>(im));
    const void* ptr = impl_->pyramids.back().get();
    config.attribute(MemoryTextureInput::kImageAttribute, OIIO::TypeDesc::PTR, &ptr);
    if (oiioAutomip) config.attribute(MemoryTextureInput::kLevelsAttribute, 1);
    OIIO::ustring name("tray:texture/" + std::to_string(i));
    if (!cache->add_file(name, &MemoryTextureInput::create, &config))
      throw Error("texture '" + im.name + "': OpenImageIO: " + cache->geterror());
    impl_->handles.push_back(ts->get_texture_handle(name));
  }
}

double TextureSampler::budgetFor(const std::vector<TextureImage>& images) {
  double bytes = 0;
  for (const TextureImage& im : images) {
    // Every MIP level (each about a quarter of the one above: 4/3 in all), three floats per
    // texel as TexturePyramid hands them over, plus 10% for OIIO's tile padding and records.
    bytes += 1.1 * (4.0 / 3.0) * double(im.width) * double(im.height) * 3 * sizeof(float);
  }
  const double needMB = std::ceil(bytes / (1024.0 * 1024.0));
  const double quarterMB = double(OIIO::Sysutil::physical_memory()) / 4 / (1024.0 * 1024.0);
  return std::max<double>(kMinCacheMB, std::min(needMB, quarterMB));
}

double TextureSampler::cacheMB() const {
  float mb = 0;
  impl_->ts->getattribute("max_memory_MB", OIIO::TypeFloat, &mb);
  return mb;
}

int64_t TextureSampler::tilesReadAgain() const {
  int64_t total = 0;
  OIIO::ImageCache* cache = impl_->ts->imagecache();
  for (size_t i = 0; i < impl_->handles.size(); ++i) {
    int64_t n = 0;
    if (cache->get_image_info(OIIO::ustring("tray:texture/" + std::to_string(i)), 0, 0,
                              OIIO::ustring("stat:redundant_tiles"), OIIO::TypeInt64, &n))
      total += n;
  }
  return total;
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
