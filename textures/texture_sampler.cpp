#include "textures/texture_sampler.h"

#include <OpenImageIO/sysutil.h>

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "textures/oiio_texture_system.h"
#include "textures/texture_lookup.h"
#include "textures/texture_pyramid.h"

namespace tray {

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
  const std::vector<TextureImage>& images;
  std::vector<std::unique_ptr<TexturePyramid>> pyramids;
  std::unique_ptr<OiioTextureSystem> oiio;  ///< null: TRay's own filter
  explicit Impl(const std::vector<TextureImage>& im) : images(im) {}
};

TextureSampler::TextureSampler(const std::vector<TextureImage>& images, double cacheMB,
                               TextureBackend backend)
    : impl_(std::make_unique<Impl>(images)), cacheMB_(cacheMB > 0 ? cacheMB : budgetFor(images)) {
  for (const TextureImage& im : images) {
    if (!im.valid()) throw Error("texture '" + im.name + "' has no pixels or a wrong pixel count");
    impl_->pyramids.push_back(std::make_unique<TexturePyramid>(im));
  }
  // TRay's filter never evicts a tile, so it runs only when all the tiles it could make fit
  // the budget; beyond that OIIO's cache pages them (same values, more time).
  const bool oiio = backend == TextureBackend::kOiio || backend == TextureBackend::kOiioAutomip ||
                    (backend == TextureBackend::kAuto && tileMBAtMost(images) > cacheMB_);
  if (oiio)
    impl_->oiio = std::make_unique<OiioTextureSystem>(impl_->pyramids, cacheMB_,
                                                      backend == TextureBackend::kOiioAutomip);
}

TextureSampler::~TextureSampler() = default;

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

double TextureSampler::tileMBAtMost(const std::vector<TextureImage>& images) {
  double bytes = 0;
  for (const TextureImage& im : images)
    bytes += double(TexturePyramid::tileBytesAtMost(im.width, im.height));
  return bytes / (1024.0 * 1024.0);
}

bool TextureSampler::paged() const {
  return impl_->oiio != nullptr;
}

int64_t TextureSampler::tilesReadAgain() const {
  return impl_->oiio ? impl_->oiio->tilesReadAgain() : 0;
}

int64_t TextureSampler::tilesMade() const {
  int64_t n = 0;
  for (const auto& p : impl_->pyramids) n += p->tilesMade();
  return n;
}

void TextureSampler::prefetch(const TextureRef& ref, Vec2 uv) const {
  if (impl_->oiio || footprintMatters(ref) || ref.image < 0 ||
      size_t(ref.image) >= impl_->pyramids.size())
    return;
  const Vec2 at = transformUv(ref, uv);
  TextureQuery q{at.x, at.y, 0, 0, 0, 0, ref.wrapS, ref.wrapT};
  prefetchLevel0(*impl_->pyramids[size_t(ref.image)], q);
}

Color TextureSampler::sample(const TextureRef& ref, const UvFootprint& f) const {
  if (ref.image < 0 || size_t(ref.image) >= impl_->pyramids.size()) return Color(1.0f);
  const TextureImage& im = impl_->images[size_t(ref.image)];
  const Vec2 uv = transformUv(ref, f.uv);
  // OIIO's t runs down the image from its first row, as glTF's v does (glTF 2.0 §3.8.4.1), so
  // uvs pass through unchanged.
  TextureQuery q{uv.x, uv.y, 0, 0, 0, 0, ref.wrapS, ref.wrapT};
  if (footprintMatters(ref)) {
    const Vec2 dx = transformUv(ref, f.dx, true), dy = transformUv(ref, f.dy, true);
    q.dsdx = dx.x, q.dtdx = dx.y, q.dsdy = dy.x, q.dtdy = dy.y;
    // Footprint in texels of the finest level: under one texel the texture is magnified.
    const float w = float(im.width), h = float(im.height);
    const float texels = std::max(std::hypot(dx.x * w, dx.y * h), std::hypot(dy.x * w, dy.y * h));
    filtersOf(texels > 1.0f ? ref.minFilter : ref.magFilter, q.texel, q.mip);
  } else {  // one filter without MIP levels: the derivatives are never read (nor by OIIO's nomip)
    filtersOf(ref.magFilter, q.texel, q.mip);
  }
  if (!impl_->oiio) return lookupTexture(*impl_->pyramids[size_t(ref.image)], q);
  float rgb[3] = {0, 0, 0};
  if (!impl_->oiio->lookup(size_t(ref.image), q, rgb))
    return Color(1.0f);  // cannot happen for images registered above; shade untextured
  return {rgb[0], rgb[1], rgb[2]};
}

}  // namespace tray
