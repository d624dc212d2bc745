#pragma once
// TRAY_shape types "curves" and "subdivision" (docs/curves-subdivision.md): Embree's own
// curves (shapes/curves.h) and Catmull-Clark subdivision surfaces (shapes/subdivision.h), with
// their data in accessors.
#include <memory>

#include "core/shape.h"
#include "gltf/gltf_context.h"
#include "gltf/gltf_value.h"

namespace tray {

/// {"type": "curves", "points": accessor (VEC4 float: x, y, z, radius), "basis": "bspline" |
/// "bezier", "profile": "round" | "flat", "strands": accessor (SCALAR unsigned: control points
/// per strand, laid end to end) or "segments": accessor (first control point of each segment);
/// neither: one strand of all points}.
std::shared_ptr<const Shape> parseCurves(const GltfContext& ctx, ExtensionReader& r);

/// {"type": "subdivision", a cage: "positions" (VEC3 float), "faceVertexCounts" and "indices"
/// (SCALAR unsigned) or "mesh": a glTF mesh index whose triangles (welded by position) are the
/// cage; "tessellationRate" (default 16), "creases" (SCALAR unsigned, vertex pairs) with
/// "creaseWeights" (SCALAR float), "corners" with "cornerWeights", "boundary": "smooth" | "pin"}.
std::shared_ptr<const Shape> parseSubdivision(const GltfContext& ctx, ExtensionReader& r);

}  // namespace tray
