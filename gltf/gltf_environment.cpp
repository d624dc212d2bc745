#include "gltf/gltf_environment.h"

#include "io/environment_map.h"

namespace tray {

void loadEnvironmentImage(const GltfContext& ctx, const ImageBytes& images, const UriPolicy& policy,
                          Scene& scene, uint64_t maxMemoryBytes) {
  Environment& env = scene.environment;
  std::vector<std::string> warnings;
  if (!env.imagePath.empty()) {
    std::string problem;
    const std::string file = policy.resolve(env.imagePath, problem);
    if (file.empty()) ctx.fail("TRAY_environment image: " + problem);
    env.map = loadEnvironmentMap(file, &warnings, maxMemoryBytes);
  } else if (env.imageIndex >= 0) {
    const tinygltf::Image& im = ctx.model.images[size_t(env.imageIndex)];
    const unsigned char* data = nullptr;
    size_t size = 0;
    if (im.bufferView >= 0) {  // gltf_validate checked that it lies inside its buffer
      const auto& bv = ctx.model.bufferViews[size_t(im.bufferView)];
      data = ctx.model.buffers[size_t(bv.buffer)].data.data() + bv.byteOffset;
      size = bv.byteLength;
    } else if (size_t(env.imageIndex) < images.byImage.size()) {
      data = images.byImage[size_t(env.imageIndex)].data();
      size = images.byImage[size_t(env.imageIndex)].size();
    }
    const std::string where = ctx.path + ": " + nameOf("image", env.imageIndex, im.name);
    if (!data || size == 0) ctx.fail(nameOf("image", env.imageIndex, im.name) + ": no image data");
    env.map = decodeEnvironmentMap(data, size, where, &warnings, maxMemoryBytes);
  }
  for (const std::string& w : warnings)
    if (ctx.report) ctx.report->warnings.push_back(w);
}

}  // namespace tray
