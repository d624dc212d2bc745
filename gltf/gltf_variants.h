#pragma once
// KHR_materials_variants: named material sets of one asset (a shoe in several colours). The root
// lists the variants; each primitive maps some of them to other materials. --variant picks one.
#include <string>
#include <vector>

#include "gltf/gltf_context.h"

namespace tray {

/// The root's variant names, in order ("" for an unnamed one). Empty without the extension.
/// Fails on a malformed list (not an array of objects, a name that is not a string).
std::vector<std::string> readVariantNames(const GltfContext& ctx);

/// Checks every primitive's mappings (material and variant indices in range), used or not.
void validateVariantMappings(const GltfContext& ctx, size_t variantCount);

/// --variant: "none" (-1: the primitives' own materials), a name or an index. Fails with the
/// list of variants for any other value.
int chooseVariant(const GltfContext& ctx, const std::vector<std::string>& names,
                  const std::string& which);

/// The material a primitive takes under `variant` (-1: its own, `material`; also when no mapping
/// names the variant, KHR_materials_variants "Primitive extension").
int variantMaterial(const tinygltf::Primitive& p, int variant);

}  // namespace tray
