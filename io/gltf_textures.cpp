#include "io/gltf_textures.h"

#include <map>
#include <utility>

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

class Binder {
 public:
  Binder(const GltfContext& ctx, const ImageBytes& bytes, Scene& scene)
      : ctx_(ctx), bytes_(bytes), scene_(scene) {}

  void bind(TextureRef& ref, bool srgb) {
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
    auto key = std::make_pair(t.source, srgb);
    auto it = decoded_.find(key);
    if (it == decoded_.end()) {
      scene_.textures.push_back(decodeImage(ctx_, bytes_, t.source, srgb, budget_));
      it = decoded_.emplace(key, int(scene_.textures.size()) - 1).first;
    }
    ref.image = it->second;
  }

 private:
  const GltfContext& ctx_;
  const ImageBytes& bytes_;
  Scene& scene_;
  std::map<std::pair<int, bool>, int> decoded_;
  uint64_t budget_ = kMaxSceneTexturePixels;
};

}  // namespace

void bindTextures(const GltfContext& ctx, const ImageBytes& bytes, Scene& scene) {
  Binder binder(ctx, bytes, scene);
  for (Material& m : scene.materials) {
    binder.bind(m.baseColorTexture, true);
    binder.bind(m.metallicRoughnessTexture, false);
    binder.bind(m.emissiveTexture, true);
    binder.bind(m.normalTexture, false);
  }
  for (TriangleMesh& mesh : scene.meshes) {
    const Material& m = scene.materials[size_t(mesh.material)];
    if (m.normalTexture.valid() && mesh.tangents.empty())
      computeTangents(mesh, m.normalTexture.texCoord);
  }
}

}  // namespace tray
