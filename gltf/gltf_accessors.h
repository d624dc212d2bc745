#pragma once
// Typed access to glTF accessor data (glTF 2.0 §3.6 "Binary Data Storage"): layout checks with
// overflow-checked arithmetic, then reads that rely on them.
#include <cstdint>
#include <vector>

#include "gltf/gltf_context.h"

namespace tray {

/// Bytes per component of a core glTF component type; 0 if the type is not allowed by glTF 2.0
/// (tinygltf also accepts INT 5124 and DOUBLE 5130).
int componentSize(int componentType);
/// Components per element of an accessor type (SCALAR 1 ... MAT4 16); 0 if unknown.
int componentCount(int type);

/// Checks every accessor's layout: component type, normalization, bufferView range, alignment,
/// stride, bounds, and its sparse substructure including the sparse indices' values.
void checkAccessors(const GltfContext& ctx);
/// Checks every bufferView against its buffer.
void checkBufferViews(const GltfContext& ctx);

/// Reads accessor `index` (layout already checked) as count x components floats, normalized
/// integers mapped per glTF 2.0 §3.11, sparse substitutions applied. Missing bufferView: zeros.
std::vector<float> readFloats(const GltfContext& ctx, int index);
/// glTF-Validator's ACCESSOR_ELEMENT_OUT_OF_MIN/MAX_BOUND, as one warning per accessor: viewers
/// and culling trust min/max, TRay renders from the data, so it warns rather than refuses.
void warnAccessorBounds(const GltfContext& ctx);
/// Reads an index accessor (SCALAR unsigned byte/short/int) as 32-bit indices.
std::vector<uint32_t> readIndices(const GltfContext& ctx, int index);

}  // namespace tray
