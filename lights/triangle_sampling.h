#pragma once
// How an emissive triangle is sampled from a receiver (`--triangle-sampling`,
// integrators/path.cpp): uniformly by area, its pdf converted to solid angle, or uniformly in
// the solid angle it subtends (Arvo 1995), or each where it pays (pbrt-v4's Triangle::Sample).
// Plain types only: the one-text files (lights/triangle_light_lanes.h) read them in scalar
// and SIMD mode alike, so they live outside those files' per-target namespaces.
#include <string>

#include "core/error.h"

namespace tray {

// In a namespace of its own: a SIMD stage passes it to the one-text templates, and an argument
// of namespace tray would make argument-dependent lookup find the scalar templates there beside
// the target's own, an ambiguous call (docs/lanes.md, "Writing one text").
namespace lane_args {
enum class TriangleSampling : int {
  kAuto,        ///< solid angle where it lies in [kMinSphericalSolidAngle, kMax...], else area
  kArea,        ///< by area everywhere (TRay before issue 37, bit for bit)
  kSolidAngle,  ///< by solid angle wherever it is defined (0 < solid angle <= kMax...)
};
}  // namespace lane_args
using lane_args::TriangleSampling;

/// pbrt-v4's MinSphericalSampleArea and MaxSphericalSampleArea (shapes.h): below the first,
/// Arvo's construction loses float precision (the sub-triangle's angles cancel); above the
/// second the triangle fills nearly a hemisphere around the receiver and its construction
/// divides by nearly zero. Steradians.
inline constexpr float kMinSphericalSolidAngle = 3e-4f;
inline constexpr float kMaxSphericalSolidAngle = 6.22f;
/// pbrt-v4's BilinearPatch::MinSphericalSampleArea: a rectangle's solid angle comes from four
/// angles near pi/2 summed less 2 pi (Urena et al. 2013), about 1e-6 sr of float error, so
/// even the forced mode (kSolidAngle) samples a rectangle by solid angle only above this.
inline constexpr float kMinSphericalRectangleSolidAngle = 1e-4f;

/// "auto", "area" or "solid-angle" (the choices of --triangle-sampling); throws tray::Error
/// otherwise.
inline TriangleSampling triangleSampling(const std::string& name) {
  if (name == "auto") return TriangleSampling::kAuto;
  if (name == "area") return TriangleSampling::kArea;
  if (name == "solid-angle") return TriangleSampling::kSolidAngle;
  throw Error("--triangle-sampling '" + name + "': expected auto, area or solid-angle");
}

}  // namespace tray
