#pragma once
// Embree's own geometry for the shapes that have no intersection routine of their own: curves
// (shapes/curves.h) and Catmull-Clark subdivision surfaces (shapes/subdivision.h).
// docs/curves-subdivision.md.
#include <embree3/rtcore.h>

#include "core/hit.h"
#include "core/shape.h"

namespace tray {

/// A committed-ready Embree geometry for `shape` (its object space), or nullptr when the shape
/// is not one Embree intersects natively.
RTCGeometry embreeNativeGeometry(RTCDevice device, const Shape& shape);

/// Whether geometry made by embreeNativeGeometry is a subdivision surface, whose hits need
/// embreeSubdivisionNormal.
bool embreeNativeIsSubdivision(const Shape& shape);

/// A subdivision hit (face hit.triangle at Embree's hit.uv): the limit surface's normal
/// dP/du x dP/dv from rtcInterpolate, octahedral-encoded into hit.b1, b2 (shapes/subdivision.h).
void embreeSubdivisionNormal(RTCGeometry g, Hit& hit);

}  // namespace tray
