#pragma once
// TRAY_environment's "image" for the scene being loaded: a file beside the glTF (under the
// loader's URI policy, like buffers and images) or one of the document's images.
#include <cstdint>

#include "core/scene.h"
#include "gltf/gltf_context.h"
#include "gltf/gltf_file_access.h"
#include "gltf/gltf_images.h"

namespace tray {

/// Loads scene.environment's image, if it names one (io/environment_map.h), into
/// scene.environment.map. Throws tray::Error "PATH: ..." for a refused, missing or bad map, or
/// one whose decoded size is over maxMemoryBytes (--max-memory; 0: none).
void loadEnvironmentImage(const GltfContext& ctx, const ImageBytes& images, const UriPolicy& policy,
                          Scene& scene, uint64_t maxMemoryBytes = 0);

}  // namespace tray
