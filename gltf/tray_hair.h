#pragma once
// TRAY_materials_hair (docs/curves-subdivision.md): Chiang et al. 2016's hair BSDF.
#include <string>

#include "core/material.h"
#include "gltf/gltf_context.h"

namespace tray {

/// Reads {"melanin", "melaninRedness"} or "color" or "absorptionCoefficient" (one way to give
/// the fibre's absorption), "roughness", "azimuthalRoughness", "ior", "cuticleAngle" into
/// m.hair, enabled.
void readHairMaterial(const GltfContext& ctx, const tinygltf::Value& ext, const std::string& where,
                      Material& m);

}  // namespace tray
