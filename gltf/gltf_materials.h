#pragma once
// glTF materials (glTF 2.0 §3.9) and their KHR_ and TRAY_ extensions into tray::Material.
#include "core/material.h"
#include "gltf/gltf_context.h"

namespace tray {

/// Converts material `index`, checking every factor's range and every texture reference.
Material convertMaterial(const GltfContext& ctx, int index);

/// The material glTF 2.0 §3.9.6 prescribes for primitives without one: every factor at its
/// default (white base color, metallic 1, roughness 1).
Material defaultGltfMaterial();

/// KHR_texture_transform (the extension's object) on a texture reference: offset, rotation
/// (radians), scale, and a texCoord that overrides the reference's own. Shared by core glTF
/// textures and those inside material extensions (gltf/gltf_material_layers.cpp).
void readTextureTransform(const GltfContext& ctx, const tinygltf::Value& transform,
                          const std::string& where, TextureRef& ref);

}  // namespace tray
