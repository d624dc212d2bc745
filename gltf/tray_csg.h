#pragma once
// The "csg" type of the TRAY_shape node extension (docs/scene-format.md, "CSG"; docs/csg.md).
#include <memory>
#include <string>

#include "gltf/gltf_value.h"
#include "shapes/csg.h"

namespace tray {

/// Reads {"type": "csg", "op": ..., "children": [node, ...]} from `r` (the node's TRAY_shape,
/// whose raw value is `value`). Operand nodes are parsed with their own transforms and
/// materials: TRAY_shape sphere / box / plane (the half-space y <= 0), csg (recursively), or a
/// glTF mesh (a closed triangle mesh). Fails on cycles, operands without a solid, operands with
/// glTF children, and on an unbounded result unless the node is itself an operand of a CSG.
std::shared_ptr<const Csg> parseCsg(const GltfContext& ctx, const tinygltf::Value& value,
                                    ExtensionReader& r, const std::string& where);

}  // namespace tray
