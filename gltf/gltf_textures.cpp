#include "gltf/gltf_textures.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <map>
#include <new>
#include <set>
#include <utility>

#include "core/error.h"
#include "shapes/mesh_tangents.h"

namespace tray {

namespace {

TextureWrap wrapOf(const GltfContext& ctx, int value, const std::string& where) {
  switch (value) {
    case TINYGLTF_TEXTURE_WRAP_REPEAT:
      return TextureWrap::kRepeat;
    case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE:
      return TextureWrap::kClampToEdge;
    case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT:
      return TextureWrap::kMirroredRepeat;
    default:
      ctx.fail(where + " has an invalid wrap mode " + std::to_string(value));
  }
}

TextureFilter filterOf(const GltfContext& ctx, int value, bool minification,
                       const std::string& where) {
  switch (value) {
    case -1:  // unstated: glTF leaves the choice to the renderer
      return minification ? TextureFilter::kLinearMipmapLinear : TextureFilter::kLinear;
    case TINYGLTF_TEXTURE_FILTER_NEAREST:
      return TextureFilter::kNearest;
    case TINYGLTF_TEXTURE_FILTER_LINEAR:
      return TextureFilter::kLinear;
    default:
      break;
  }
  if (minification) {
    switch (value) {
      case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST:
        return TextureFilter::kNearestMipmapNearest;
      case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_NEAREST:
        return TextureFilter::kLinearMipmapNearest;
      case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR:
        return TextureFilter::kNearestMipmapLinear;
      case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR:
        return TextureFilter::kLinearMipmapLinear;
      default:
        break;
    }
  }
  ctx.fail(where + " has an invalid " + (minification ? "minFilter " : "magFilter ") +
           std::to_string(value));
}

/// Binds references in a first pass (cheap), then decodes each image used: headers in order
/// (so the caps fail deterministically and before memory is spent), pixels in parallel.
class Binder {
 public:
  Binder(const GltfContext& ctx, Scene& scene) : ctx_(ctx), scene_(scene) {}

  /// alpha: the image's alpha channel is needed too (an alpha-tested base colour).
  void bind(TextureRef& ref, bool srgb, bool alpha = false) {
    if (ref.image < 0) return;
    // convertMaterial checked the texture index is in range.
    const int textureIndex = ref.image;
    const tinygltf::Texture& t = ctx_.model.textures[size_t(textureIndex)];
    const std::string where = nameOf("texture", textureIndex, t.name);
    if (t.source < 0) ctx_.fail(where + " has no image 'source' (only PNG/JPEG sources are read)");
    if (t.sampler >= 0) {
      const tinygltf::Sampler& s = ctx_.model.samplers[size_t(t.sampler)];
      const std::string sw = nameOf("sampler", t.sampler, s.name);
      ref.wrapS = wrapOf(ctx_, s.wrapS, sw);
      ref.wrapT = wrapOf(ctx_, s.wrapT, sw);
      ref.magFilter = filterOf(ctx_, s.magFilter, false, sw);
      ref.minFilter = filterOf(ctx_, s.minFilter, true, sw);
    }
    auto [it, added] = slots_.emplace(std::make_pair(t.source, srgb), int(slots_.size()));
    if (added) {
      if (std::find(sources_.begin(), sources_.end(), t.source) == sources_.end())
        sources_.push_back(t.source);
    }
    if (alpha) withAlpha_.insert(t.source);
    ref.image = it->second;
  }

  void decode(const ImageBytes& bytes, MemoryEstimate& memory, uint64_t maxMemoryBytes) {
    std::vector<ImageInfo> infos;
    uint64_t total = 0;
    for (int source : sources_) {
      infos.push_back(inspectImage(ctx_, bytes, source));
      total += infos.back().pixels() *
               uint64_t(slots_.count({source, true}) + slots_.count({source, false}));
      if (total > kMaxSceneTexturePixels)
        ctx_.fail(infos.back().where + ": the scene's textures exceed the limit of " +
                  std::to_string(kMaxSceneTexturePixels) + " pixels in all");
      memory.textures += infos.back().codeBytes();
    }
    checkMemory(ctx_.path, memory, maxMemoryBytes);
    scene_.textures.resize(slots_.size());
    std::vector<std::string> problems(infos.size());
    tbb::parallel_for(size_t(0), infos.size(), [&](size_t i) {
      const int source = infos[i].index;
      auto srgb = slots_.find({source, true}), linear = slots_.find({source, false});
      TextureImage out[2];
      try {
        decodeImage(ctx_, infos[i], srgb != slots_.end(), linear != slots_.end(), out,
                    withAlpha_.count(source) != 0);
      } catch (const std::bad_alloc&) {  // not a problem of the file: main reports it
        throw;
      } catch (const std::exception& e) {
        problems[i] = e.what();
        return;
      }
      if (srgb != slots_.end()) scene_.textures[size_t(srgb->second)] = std::move(out[0]);
      if (linear != slots_.end()) scene_.textures[size_t(linear->second)] = std::move(out[1]);
    });
    for (const std::string& p : problems)
      if (!p.empty()) throw Error(p);  // already "PATH: image N: problem"
  }

 private:
  const GltfContext& ctx_;
  Scene& scene_;
  std::map<std::pair<int, bool>, int> slots_;  ///< (image, sRGB) -> Scene::textures index
  std::vector<int> sources_;                   ///< images in order of first use
  std::set<int> withAlpha_;                    ///< images whose alpha is read
};

}  // namespace

void bindTextures(const GltfContext& ctx, const ImageBytes& bytes, Scene& scene,
                  MemoryEstimate& memory, uint64_t maxMemoryBytes) {
  Binder binder(ctx, scene);
  for (Material& m : scene.materials) {
    binder.bind(m.baseColorTexture, true, m.alphaMode != AlphaMode::kOpaque);
    binder.bind(m.metallicRoughnessTexture, false);
    binder.bind(m.emissiveTexture, true);
    binder.bind(m.normalTexture, false);
    MaterialLayers& l = m.layers;  // KHR_materials_specular, _clearcoat, _sheen (sRGB: colours)
    binder.bind(l.specularTexture, false, true);
    binder.bind(l.specularColorTexture, true);
    binder.bind(l.clearcoatTexture, false);
    binder.bind(l.clearcoatRoughnessTexture, false);
    binder.bind(l.clearcoatNormalTexture, false);
    binder.bind(l.sheenColorTexture, true);
    binder.bind(l.sheenRoughnessTexture, false, true);
    binder.bind(l.anisotropyTexture, false);                 // KHR_materials_anisotropy: linear RGB
    binder.bind(l.diffuseTransmissionTexture, false, true);  // _diffuse_transmission: A
    binder.bind(l.diffuseTransmissionColorTexture, true);
    binder.bind(l.iridescenceTexture, false);
    binder.bind(l.iridescenceThicknessTexture, false);
  }
  binder.decode(bytes, memory, maxMemoryBytes);
  for (TriangleMesh& mesh : scene.meshes) {
    const Material& m = scene.materials[size_t(mesh.material)];
    if (m.normalTexture.valid() && mesh.tangents.empty())
      computeTangents(mesh, m.normalTexture.texCoord);
    // KHR_materials_anisotropy's direction lives in the same tangent space.
    if (m.layers.anisotropyStrength > 0 && mesh.tangents.empty())
      computeTangents(mesh,
                      m.layers.anisotropyTexture.valid() ? m.layers.anisotropyTexture.texCoord : 0);
  }
}

}  // namespace tray
