#pragma once
// The TRAY_shape node extension: an analytic shape in place of (or instead of) a mesh.
#include <memory>
#include <string>

#include "core/shape.h"
#include "gltf/gltf_context.h"

namespace tray {

struct TrayShape {
  std::shared_ptr<const Shape> shape;
  int material = -1;  ///< glTF material index; -1: the default material
};

/// Parses a TRAY_shape object (docs/scene-format.md): {"type": "sphere" | "plane" | "box" |
/// "torus" | "cylinder" | "cone" | "paraboloid" | "hyperboloid" | "disk" | "csg" | "curves" |
/// "subdivision" (gltf/tray_curves.h), ...,
/// "material": index}. Every number must be finite, sizes positive, box min < max; unknown keys
/// and unknown types are errors. `where` names the node in messages.
TrayShape parseTrayShape(const GltfContext& ctx, const tinygltf::Value& value,
                         const std::string& where);

}  // namespace tray
