#include "materials/iridescence.h"

#include <algorithm>
#include <cmath>

namespace tray {

namespace {

float sq(float x) {
  return x * x;
}

/// Schlick's reflectance at cos (the reference's F_Schlick(f0, 1, cos)).
float schlick(float f0, float c) {
  const float m = std::clamp(1.0f - c, 0.0f, 1.0f);
  return f0 + (1.0f - f0) * (m * m) * (m * m) * m;
}

float iorToF0(float transmitted, float incident) {
  return sq((transmitted - incident) / (transmitted + incident));
}

/// The CIE 1931 XYZ sensitivities' Fourier transform at optical path difference opd (nm) with
/// phase shift `shift` per channel, from Belcour & Barla's Gaussian fits (supplemental code;
/// iridescence.glsl's evalSensitivity), normalised by the integral of y-bar, then converted to
/// linear Rec.709 (sRGB primaries, D65) with the usual XYZ -> Rec.709 matrix.
Color evalSensitivity(float opd, const Color& shift) {
  constexpr double kTwoPi = 2.0 * 3.14159265358979323846;
  const double phase = kTwoPi * double(opd) * 1.0e-9;
  const double val[3] = {5.4856e-13, 4.4201e-13, 5.2481e-13};
  const double pos[3] = {1.6810e+06, 1.7953e+06, 2.2084e+06};
  const double var[3] = {4.3278e+09, 9.3046e+09, 6.6121e+09};
  const double sh[3] = {shift.x, shift.y, shift.z};
  double xyz[3];
  for (int i = 0; i < 3; ++i)
    xyz[i] = val[i] * std::sqrt(kTwoPi * var[i]) * std::cos(pos[i] * phase + sh[i]) *
             std::exp(-phase * phase * var[i]);
  xyz[0] += 9.7470e-14 * std::sqrt(kTwoPi * 4.5282e+09) * std::cos(2.2399e+06 * phase + sh[0]) *
            std::exp(-4.5282e+09 * phase * phase);
  for (double& v : xyz) v /= 1.0685e-7;
  return {float(3.2404542 * xyz[0] - 1.5371385 * xyz[1] - 0.4985314 * xyz[2]),
          float(-0.9692660 * xyz[0] + 1.8760108 * xyz[1] + 0.0415560 * xyz[2]),
          float(0.0556434 * xyz[0] - 0.2040259 * xyz[1] + 1.0572252 * xyz[2])};
}

}  // namespace

Color iridescentFresnel(float outsideIor, float filmIor, float cosTheta1, float thicknessNm,
                        const Color& baseF0) {
  cosTheta1 = std::clamp(std::fabs(cosTheta1), 0.0f, 1.0f);
  // The film's IOR fades to the outside's as the thickness goes to 0 (smoothstep over 0-30
  // nm), so that a vanishing film leaves the base's reflectance (the reference's rule).
  const float t = std::clamp(thicknessNm / 0.03f, 0.0f, 1.0f);
  const float film = outsideIor + (filmIor - outsideIor) * (t * t * (3.0f - 2.0f * t));
  // Snell's law into the film; total internal reflection reflects everything.
  const float sin2Theta2 = sq(outsideIor / film) * (1.0f - sq(cosTheta1));
  const float cos2Theta2 = 1.0f - sin2Theta2;
  if (cos2Theta2 < 0) return Color(1.0f);
  const float cosTheta2 = std::sqrt(cos2Theta2);
  // First interface (outside -> film): reflectance, transmittance there and back, and the
  // phase shift on reflection (pi where the film is the optically thinner side).
  const float r12 = schlick(iorToF0(film, outsideIor), cosTheta1);
  const float t121 = 1.0f - r12;
  const float phi12 = film < outsideIor ? kPi : 0.0f;
  const float phi21 = kPi - phi12;
  // Second interface (film -> base), per channel: the base's IOR from its F0 (against air).
  Color result;
  const float f0[3] = {baseF0.x, baseF0.y, baseF0.z};
  float r23[3], phi23[3], r123[3], rs[3];
  for (int c = 0; c < 3; ++c) {
    const float s = std::sqrt(std::clamp(f0[c], 0.0f, 0.9999f));
    const float baseIor = (1.0f + s) / (1.0f - s);
    r23[c] = schlick(iorToF0(baseIor, film), cosTheta2);
    phi23[c] = baseIor < film ? kPi : 0.0f;
    const float r = std::clamp(r12 * r23[c], 1e-5f, 0.9999f);
    r123[c] = std::sqrt(r);
    rs[c] = sq(t121) * r23[c] / (1.0f - r);
  }
  // The Airy sum as a DC term (m = 0) plus the first two pairs of Diracs (m = 1, 2), each
  // integrated against the sensitivities at m times the optical path difference.
  const float opd = 2.0f * film * thicknessNm * cosTheta2;
  float I[3], cm[3];
  for (int c = 0; c < 3; ++c) I[c] = r12 + rs[c], cm[c] = rs[c] - t121;
  for (int m = 1; m <= 2; ++m) {
    const Color shift(float(m) * (phi21 + phi23[0]), float(m) * (phi21 + phi23[1]),
                      float(m) * (phi21 + phi23[2]));
    const Color sm = 2.0f * evalSensitivity(float(m) * opd, shift);
    const float smc[3] = {sm.x, sm.y, sm.z};
    for (int c = 0; c < 3; ++c) {
      cm[c] *= r123[c];
      I[c] += cm[c] * smc[c];
    }
  }
  result = {std::max(I[0], 0.0f), std::max(I[1], 0.0f), std::max(I[2], 0.0f)};
  return result;
}

}  // namespace tray
