#pragma once
#include "core/math.h"

namespace tray {

/// KHR_materials_iridescence's thin-film Fresnel (docs/materials-iridescence-dispersion.md):
/// Belcour & Barla 2017, "A Practical Extension to Microfacet Theory for the Modeling of
/// Varying Iridescence" (ACM TOG 36(4)), as the extension's reference implementation writes it
/// (glTF-Sample-Viewer, iridescence.glsl, evalIridescence): the Airy sum of a film of IOR
/// filmIor and thickness thicknessNm (nanometres) between the outside (outsideIor) and a base
/// of normal-incidence reflectance baseF0, each interface's reflectance by Schlick, the
/// oscillating terms (m = 1, 2) integrated against the CIE 1931 XYZ sensitivities through their
/// Gaussian fits in Fourier space, then XYZ -> linear Rec.709. cosTheta1 is the cosine in the
/// outside medium (the microfacet cosine). Returns the RGB reflectance, clamped at 0.
Color iridescentFresnel(float outsideIor, float filmIor, float cosTheta1, float thicknessNm,
                        const Color& baseF0);

/// The extension's mix: (1 - factor) plain + factor film. A factor of 0 or a thickness of 0
/// (the reference's rule: no film) returns `plain` itself, bit for bit.
inline bool iridescenceApplies(float factor, float thicknessNm) {
  return factor > 0 && thicknessNm > 0;
}

}  // namespace tray
