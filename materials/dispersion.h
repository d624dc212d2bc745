#pragma once
#include "core/math.h"

namespace tray {

/// KHR_materials_dispersion (docs/materials-iridescence-dispersion.md): the IOR at wavelength
/// lambdaNm (nanometres) of a material with IOR nd (at the Fraunhofer d line, 587.56 nm) and
/// dispersion = 20 / V_d (Abbe number), by the extension's Cauchy form
///   n(lambda) = nd + (nd - 1) / V_d (523655 / lambda^2 - 1.5168).
/// dispersion 0 gives nd.
inline float dispersiveIor(float nd, float dispersion, float lambdaNm) {
  return nd + (nd - 1.0f) * (dispersion / 20.0f) * (523655.0f / (lambdaNm * lambdaNm) - 1.5168f);
}

/// One wavelength for a path that meets dispersive glass, and the RGB weight its radiance
/// carries from there on: w_c(lambda) = rbar_c(lambda) / (N_c p(lambda)), with rbar_c the CIE
/// 1931 2-degree matching functions (Wyman, Sloan & Shirley 2013 multi-lobe fit) taken to
/// linear Rec.709, negative lobes clamped to 0, N_c = integral of rbar_c (so that a flat
/// spectrum stays white), and p the pdf lambda is drawn with: the mean of the three normalised
/// curves, tabulated in 1 nm bins over [360, 830] nm. E[w_c] = 1 for every channel.
struct WavelengthSample {
  float lambda = 0;  ///< nanometres
  Color weight{1.0f};
  float pdf = 0;  ///< per nanometre
};
WavelengthSample sampleWavelength(float u);
/// The pdf sampleWavelength draws lambda with, and the normalised curves rbar_c / N_c there.
float wavelengthPdf(float lambdaNm);
Color wavelengthResponse(float lambdaNm);
/// The same matching functions without the clamp (exact colorimetry, signed), normalised by
/// the same N_c: the reference the clamp's error is measured against (tests).
Color wavelengthResponseSigned(float lambdaNm);
/// CIE 1931 XYZ matching functions at lambdaNm (the Wyman et al. 2013 multi-lobe fit).
Vec3 cieXyzFit(float lambdaNm);

constexpr float kWavelengthMin = 360.0f, kWavelengthMax = 830.0f;

}  // namespace tray
