#include "textures/oiio_texture_system.h"

#include <OpenImageIO/imagecache.h>
#include <OpenImageIO/imageio.h>
#include <OpenImageIO/texture.h>

#include <string>

#include "core/error.h"

namespace tray {

namespace {

using OIIO::TextureOpt;

/// Serves one TexturePyramid to OIIO's ImageCache as a float RGB scanline image with one MIP
/// level per pyramid level, rows made as OIIO asks for them. The pyramid arrives as a pointer
/// in the open() configuration (ImageCache::add_file passes it through), since an
/// ImageInput::Creator is a plain function without state.
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

TextureOpt::MipMode mipModeOf(MipFilter m) {
  switch (m) {
    case MipFilter::kNone:
      return TextureOpt::MipModeNoMIP;
    case MipFilter::kOneLevel:
      return TextureOpt::MipModeOneLevel;
    case MipFilter::kTrilinear:
      break;
  }
  return TextureOpt::MipModeTrilinear;
}

std::string fileName(size_t index) {
  return "tray:texture/" + std::to_string(index);
}

}  // namespace

struct OiioTextureSystem::Impl {
  OIIO::TextureSystem* ts = nullptr;
  std::vector<OIIO::TextureSystem::TextureHandle*> handles;
};

OiioTextureSystem::OiioTextureSystem(const std::vector<std::unique_ptr<TexturePyramid>>& pyramids,
                                     double cacheMB, bool automip)
    : impl_(std::make_unique<Impl>()) {
  // A private TextureSystem (shared = false): its cache settings are TRay's alone. Each image
  // arrives MIP-mapped, read in 64-row strips (autotile); the cache holds at most
  // max_memory_MB of tiles. automip stays on for `automip` (tests): OIIO then makes the levels.
  OIIO::TextureSystem* ts = OIIO::TextureSystem::create(false);
  impl_->ts = ts;
  ts->attribute("automip", 1);
  ts->attribute("autotile", 64);
  ts->attribute("deduplicate", 0);
  ts->attribute("max_memory_MB", float(cacheMB));
  OIIO::ImageCache* cache = ts->imagecache();
  for (size_t i = 0; i < pyramids.size(); ++i) {
    OIIO::ImageSpec config;
    const void* ptr = pyramids[i].get();
    config.attribute(MemoryTextureInput::kImageAttribute, OIIO::TypeDesc::PTR, &ptr);
    if (automip) config.attribute(MemoryTextureInput::kLevelsAttribute, 1);
    OIIO::ustring name(fileName(i));
    if (!cache->add_file(name, &MemoryTextureInput::create, &config))
      throw Error("texture '" + pyramids[i]->image().name + "': OpenImageIO: " + cache->geterror());
    impl_->handles.push_back(ts->get_texture_handle(name));
  }
}

OiioTextureSystem::~OiioTextureSystem() {
  OIIO::TextureSystem::destroy(impl_->ts);
}

bool OiioTextureSystem::lookup(size_t index, const TextureQuery& q, float rgb[3]) const {
  TextureOpt opt;
  opt.swrap = wrapOf(q.wrapS);
  opt.twrap = wrapOf(q.wrapT);
  opt.interpmode =
      q.texel == TexelFilter::kClosest ? TextureOpt::InterpClosest : TextureOpt::InterpBilinear;
  opt.mipmode = mipModeOf(q.mip);
  return impl_->ts->texture(impl_->handles[index], impl_->ts->get_perthread_info(), opt, q.s, q.t,
                            q.dsdx, q.dtdx, q.dsdy, q.dtdy, 3, rgb);
}

double OiioTextureSystem::cacheMB() const {
  float mb = 0;
  impl_->ts->getattribute("max_memory_MB", OIIO::TypeFloat, &mb);
  return mb;
}

int64_t OiioTextureSystem::tilesReadAgain() const {
  int64_t total = 0;
  OIIO::ImageCache* cache = impl_->ts->imagecache();
  for (size_t i = 0; i < impl_->handles.size(); ++i) {
    int64_t n = 0;
    if (cache->get_image_info(OIIO::ustring(fileName(i)), 0, 0,
                              OIIO::ustring("stat:redundant_tiles"), OIIO::TypeInt64, &n))
      total += n;
  }
  return total;
}

}  // namespace tray
