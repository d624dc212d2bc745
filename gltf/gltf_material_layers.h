#pragma once
// The layered-material extensions of a glTF material: KHR_materials_volume, _specular,
// _clearcoat and _sheen (docs/path-tracing.md, "Material layers").
#include "core/material.h"
#include "gltf/gltf_context.h"

namespace tray {

/// Reads the layer extensions of material `g` into m.layers, checking each factor's range and
/// naming the field in errors. Texture references keep the glTF texture index (bound later by
/// gltf/gltf_textures.cpp, like the core textures).
void readMaterialLayers(const GltfContext& ctx, const tinygltf::Material& g,
                        const std::string& where, Material& m);

}  // namespace tray
