#include "materials/hair_lobe.h"

#include <algorithm>
#include <cmath>

#include "materials/fresnel.h"

namespace tray {
namespace {

float safeSqrt(float x) {
  return std::sqrt(std::max(0.0f, x));
}
float safeAsin(float x) {
  return std::asin(std::clamp(x, -1.0f, 1.0f));
}
float sqr(float x) {
  return x * x;
}

// Modified Bessel function of the first kind, order 0, by its series (pbrt-v4 B.2 I0).
float besselI0(float x) {
  float val = 0, x2i = 1;
  int64_t ifact = 1, i4 = 1;
  for (int i = 0; i < 10; ++i) {
    if (i > 1) ifact *= i;
    val += x2i / (float(i4) * sqr(float(ifact)));
    x2i *= x * x;
    i4 *= 4;
  }
  return val;
}

float logBesselI0(float x) {
  if (x > 12) return x + 0.5f * (-std::log(2 * kPi) + std::log(1 / x) + 1 / (8 * x));
  return std::log(besselI0(x));
}

// The longitudinal scattering function (d'Eon et al. 2011), normalised over the sphere; the
// small-variance branch works in logarithms to stay finite (pbrt-v4 9.9.1).
float mp(float cosThetaI, float cosThetaO, float sinThetaI, float sinThetaO, float v) {
  float a = cosThetaI * cosThetaO / v, b = sinThetaI * sinThetaO / v;
  if (v <= 0.1f) return std::exp(logBesselI0(a) - b - 1 / v + 0.6931f + std::log(1 / (2 * v)));
  return std::exp(-b) * besselI0(a) / (std::sinh(1 / v) * 2 * v);
}

float logistic(float x, float s) {
  x = std::fabs(x);
  return std::exp(-x / s) / (s * sqr(1 + std::exp(-x / s)));
}
float logisticCdf(float x, float s) {
  return 1 / (1 + std::exp(-x / s));
}
float trimmedLogistic(float x, float s, float a, float b) {
  return logistic(x, s) / (logisticCdf(b, s) - logisticCdf(a, s));
}
float sampleTrimmedLogistic(float u, float s, float a, float b) {
  float k = logisticCdf(b, s) - logisticCdf(a, s);
  float x = -s * std::log(1 / (u * k + logisticCdf(a, s)) - 1);
  return std::clamp(x, a, b);
}

// Azimuth after p internal paths (Chiang et al. 2016, equation 4; pbrt-v4 9.9.5).
float phiOf(int p, float gammaO, float gammaT) {
  return 2 * p * gammaT - 2 * gammaO + p * kPi;
}

float np(float phi, int p, float s, float gammaO, float gammaT) {
  float dphi = phi - phiOf(p, gammaO, gammaT);
  dphi = std::remainder(dphi, 2 * kPi);  // to [-pi, pi]
  return trimmedLogistic(dphi, s, -kPi, kPi);
}

float average(const Color& c) {
  return (c.x + c.y + c.z) / 3;
}

}  // namespace

HairLobe::HairLobe(float h, float eta, const Color& sigmaA, float betaM, float betaN,
                   float alphaDegrees)
    : h_(std::clamp(h, -1.0f, 1.0f)), gammaO_(safeAsin(h)), eta_(eta), sigmaA_(sigmaA) {
  // Longitudinal variance from beta_m and logistic scale from beta_n: Chiang et al.'s fits
  // (section 4.1, equations 7 and 8).
  v_[0] = sqr(0.726f * betaM + 0.812f * sqr(betaM) + 3.7f * std::pow(betaM, 20.0f));
  v_[1] = 0.25f * v_[0];
  v_[2] = 4 * v_[0];
  for (int p = 3; p <= kPMax; ++p) v_[p] = v_[2];
  s_ =
      std::sqrt(kPi / 8) * (0.265f * betaN + 1.194f * sqr(betaN) + 5.372f * std::pow(betaN, 22.0f));
  sin2kAlpha_[0] = std::sin(alphaDegrees * kPi / 180);
  cos2kAlpha_[0] = safeSqrt(1 - sqr(sin2kAlpha_[0]));
  for (int i = 1; i < 3; ++i) {
    sin2kAlpha_[i] = 2 * cos2kAlpha_[i - 1] * sin2kAlpha_[i - 1];
    cos2kAlpha_[i] = sqr(cos2kAlpha_[i - 1]) - sqr(sin2kAlpha_[i - 1]);
  }
}

void HairLobe::tilted(int p, float sinThetaO, float cosThetaO, float& sinP, float& cosP) const {
  // R is tilted by -2 alpha, TT by alpha, TRT by 4 alpha (Chiang et al. 2016, section 4.1).
  if (p == 0) {
    sinP = sinThetaO * cos2kAlpha_[1] - cosThetaO * sin2kAlpha_[1];
    cosP = cosThetaO * cos2kAlpha_[1] + sinThetaO * sin2kAlpha_[1];
  } else if (p == 1) {
    sinP = sinThetaO * cos2kAlpha_[0] + cosThetaO * sin2kAlpha_[0];
    cosP = cosThetaO * cos2kAlpha_[0] - sinThetaO * sin2kAlpha_[0];
  } else if (p == 2) {
    sinP = sinThetaO * cos2kAlpha_[2] + cosThetaO * sin2kAlpha_[2];
    cosP = cosThetaO * cos2kAlpha_[2] - sinThetaO * sin2kAlpha_[2];
  } else {
    sinP = sinThetaO, cosP = cosThetaO;
  }
  cosP = std::fabs(cosP);  // out-of-range cosines from the tilt
}

std::array<Color, HairLobe::kPMax + 1> HairLobe::attenuation(float cosThetaO,
                                                             const Color& T) const {
  // A_p (pbrt-v4 9.9.4): Fresnel at the first crossing, then (1-f)^2 T (T f)^(p-1); the residual
  // sums the geometric series of the rest.
  std::array<Color, kPMax + 1> ap;
  float cosGammaO = safeSqrt(1 - sqr(h_));
  float f = fresnelDielectric(cosThetaO * cosGammaO, eta_);
  ap[0] = Color(f);
  ap[1] = sqr(1 - f) * T;
  for (int p = 2; p < kPMax; ++p) ap[p] = ap[p - 1] * T * f;
  Color tf = T * f;
  ap[kPMax] = ap[kPMax - 1] * tf / (Color(1.0f) - tf);
  for (float* c : {&ap[kPMax].x, &ap[kPMax].y, &ap[kPMax].z})
    if (!std::isfinite(*c)) *c = 0;
  return ap;
}

namespace {
// The absorption along one internal chord: exp(-sigma_a 2 cos(gamma_t) / cos(theta_t)).
struct Refracted {
  float gammaT;
  Color T;
};
Refracted refracted(float sinThetaO, float cosThetaO, float h, float eta, const Color& sigmaA) {
  float sinThetaT = sinThetaO / eta;
  float cosThetaT = safeSqrt(1 - sqr(sinThetaT));
  // The modified index for the projection into the normal plane (Bravais' index).
  float etap = safeSqrt(sqr(eta) - sqr(sinThetaO)) / cosThetaO;
  float sinGammaT = h / etap;
  float cosGammaT = safeSqrt(1 - sqr(sinGammaT));
  float len = 2 * cosGammaT / cosThetaT;
  return {safeAsin(sinGammaT),
          {std::exp(-sigmaA.x * len), std::exp(-sigmaA.y * len), std::exp(-sigmaA.z * len)}};
}
}  // namespace

std::array<float, HairLobe::kPMax + 1> HairLobe::lobePdf(float cosThetaO) const {
  float sinThetaO = safeSqrt(1 - sqr(cosThetaO));
  auto ap = attenuation(cosThetaO, refracted(sinThetaO, cosThetaO, h_, eta_, sigmaA_).T);
  std::array<float, kPMax + 1> pdf;
  float sum = 0;
  for (int p = 0; p <= kPMax; ++p) sum += (pdf[size_t(p)] = average(ap[size_t(p)]));
  for (float& x : pdf) x = sum > 0 ? x / sum : 0;
  return pdf;
}

Color HairLobe::evalProjected(const Vec3& wo, const Vec3& wi) const {
  float sinThetaO = wo.x, cosThetaO = safeSqrt(1 - sqr(sinThetaO));
  float phiO = std::atan2(wo.z, wo.y);
  float sinThetaI = wi.x, cosThetaI = safeSqrt(1 - sqr(sinThetaI));
  float phiI = std::atan2(wi.z, wi.y);
  Refracted r = refracted(sinThetaO, cosThetaO, h_, eta_, sigmaA_);
  float phi = phiI - phiO;
  auto ap = attenuation(cosThetaO, r.T);
  Color sum(0.0f);
  for (int p = 0; p < kPMax; ++p) {
    float sinP, cosP;
    tilted(p, sinThetaO, cosThetaO, sinP, cosP);
    sum += ap[size_t(p)] *
           (mp(cosThetaI, cosP, sinThetaI, sinP, v_[p]) * np(phi, p, s_, gammaO_, r.gammaT));
  }
  sum += ap[kPMax] * (mp(cosThetaI, cosThetaO, sinThetaI, sinThetaO, v_[kPMax]) / (2 * kPi));
  return sum;
}

float HairLobe::pdf(const Vec3& wo, const Vec3& wi) const {
  float sinThetaO = wo.x, cosThetaO = safeSqrt(1 - sqr(sinThetaO));
  float phiO = std::atan2(wo.z, wo.y);
  float sinThetaI = wi.x, cosThetaI = safeSqrt(1 - sqr(sinThetaI));
  float phiI = std::atan2(wi.z, wi.y);
  float gammaT = refracted(sinThetaO, cosThetaO, h_, eta_, sigmaA_).gammaT;
  auto apPdf = lobePdf(cosThetaO);
  float phi = phiI - phiO, pdf = 0;
  for (int p = 0; p < kPMax; ++p) {
    float sinP, cosP;
    tilted(p, sinThetaO, cosThetaO, sinP, cosP);
    pdf += mp(cosThetaI, cosP, sinThetaI, sinP, v_[p]) * apPdf[size_t(p)] *
           np(phi, p, s_, gammaO_, gammaT);
  }
  pdf += mp(cosThetaI, cosThetaO, sinThetaI, sinThetaO, v_[kPMax]) * apPdf[kPMax] / (2 * kPi);
  return pdf;
}

BsdfSample HairLobe::sample(const Vec3& wo, float uc, Vec2 u) const {
  float sinThetaO = wo.x, cosThetaO = safeSqrt(1 - sqr(sinThetaO));
  float phiO = std::atan2(wo.z, wo.y);
  // Pick the lobe by its share of A_p, and reuse uc (rescaled) for the azimuth.
  auto apPdf = lobePdf(cosThetaO);
  int p = 0;
  while (p < kPMax && uc >= apPdf[size_t(p)]) uc -= apPdf[size_t(p++)];
  if (apPdf[size_t(p)] <= 0) return {};
  uc = std::min(uc / apPdf[size_t(p)], 0x1.fffffep-1f);
  float sinP, cosP;
  tilted(p, sinThetaO, cosThetaO, sinP, cosP);
  // M_p by d'Eon et al.'s sampling (pbrt-v4 9.9.7): the cone cosine, then a uniform rotation.
  float cosTheta = 1 + v_[p] * std::log(std::max(u.x, 1e-5f) + (1 - u.x) * std::exp(-2 / v_[p]));
  float sinTheta = safeSqrt(1 - sqr(cosTheta));
  float cosPhi = std::cos(2 * kPi * u.y);
  float sinThetaI = std::clamp(-cosTheta * sinP + sinTheta * cosPhi * cosP, -1.0f, 1.0f);
  float cosThetaI = safeSqrt(1 - sqr(sinThetaI));
  float gammaT = refracted(sinThetaO, cosThetaO, h_, eta_, sigmaA_).gammaT;
  float dphi = p < kPMax ? phiOf(p, gammaO_, gammaT) + sampleTrimmedLogistic(uc, s_, -kPi, kPi)
                         : 2 * kPi * uc;
  float phiI = phiO + dphi;
  BsdfSample s;
  s.wi = {sinThetaI, cosThetaI * std::cos(phiI), cosThetaI * std::sin(phiI)};
  s.pdf = pdf(wo, s.wi);
  s.f = evalProjected(wo, s.wi);
  return s;
}

Color HairLobe::sigmaAFromConcentration(float eumelanin, float pheomelanin) {
  const Color eu(0.419f, 0.697f, 1.37f), pheo(0.187f, 0.4f, 1.05f);
  return eu * eumelanin + pheo * pheomelanin;
}

Color HairLobe::sigmaAFromReflectance(const Color& c, float betaN) {
  float d = 5.969f - 0.215f * betaN + 2.532f * sqr(betaN) - 10.73f * std::pow(betaN, 3.0f) +
            5.574f * std::pow(betaN, 4.0f) + 0.245f * std::pow(betaN, 5.0f);
  auto one = [&](float x) { return sqr(std::log(std::max(x, 1e-4f)) / d); };
  return {one(c.x), one(c.y), one(c.z)};
}

}  // namespace tray
