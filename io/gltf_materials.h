#pragma once
// glTF materials (glTF 2.0 §3.9) and their KHR_ and TRAY_ extensions into tray::Material.
#include "core/material.h"
#include "io/gltf_context.h"

namespace tray {

/// Converts material `index`, checking every factor's range and every texture reference.
Material convertMaterial(const GltfContext& ctx, int index);

/// The material glTF 2.0 §3.9.6 prescribes for primitives without one: every factor at its
/// default (white base color, metallic 1, roughness 1).
Material defaultGltfMaterial();

}  // namespace tray
