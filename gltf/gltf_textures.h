#pragma once
// Binds materials' texture references to decoded images and glTF samplers (glTF 2.0 §3.8).
#include "core/scene.h"
#include "gltf/gltf_context.h"
#include "gltf/gltf_images.h"
#include "io/memory_estimate.h"

namespace tray {

/// For every texture reference of scene.materials (which convertMaterial left holding the glTF
/// texture index): checks the texture's source and sampler, copies the sampler's wrap modes and
/// filters into the reference, and points it at a Scene::textures entry, decoding each
/// (image, sRGB or linear) pair once. baseColor and emissive textures are sRGB-encoded (glTF
/// 2.0 §3.9.2, §3.9.5), metallicRoughness and normal textures linear. Then gives meshes whose
/// material has a normal texture but no TANGENT computed tangents. Before decoding, adds the
/// images' compact size to memory.textures and checks it against maxMemoryBytes (0: none).
void bindTextures(const GltfContext& ctx, const ImageBytes& bytes, Scene& scene,
                  MemoryEstimate& memory, uint64_t maxMemoryBytes = 0);

}  // namespace tray
