// KHR_materials_sheen over the metallic-roughness base, by the albedo scaling of Conty Estevez
// & Kulla 2017 as the extension README ("Sheen layering") gives it:
//   f = sheenColor f_charlie + f_base min(1 - s E(cos_o), 1 - s E(cos_i)),  s = max(sheenColor)
// where E is the Charlie BRDF's directional albedo (materials/sheen.cpp). The sheen reflects
// at most s E(cos_o) and the base keeps at most 1 - s E(cos_o): energy is conserved, and the
// min of both directions keeps the base term symmetric. The clearcoat, if any, lies on top.
#include "materials/bsdf.h"

namespace tray {

namespace {
/// As for the clearcoat: the base's share of sampling never drops to 0.
constexpr float kMinBaseEstimate = 0.05f;
}  // namespace

void Bsdf::initSheen(const ShadingMaterial& m) {
  sheenOn_ = true;
  sheenColor_.value = max(m.sheenColor, Color(0.0f));
  sheenMax_ = std::min(maxComponent(sheenColor_.value), 1.0f);
  sheen_.value = CharlieSheen(m.sheenRoughness);
  if (clearcoat_ == 0)  // otherwise initClearcoat set it
    baseEstimate_ = std::clamp(maxComponent(m.baseColor), kMinBaseEstimate, 1.0f);
}

float Bsdf::sheenProbability(float sE) const {
  // The sheen's share of the reflected energy against the base's.
  const float base = (1.0f - sE) * baseEstimate_;
  return sE > 0 ? sE / (sE + base) : 0.0f;
}

Color Bsdf::sheenEval(const Vec3& wo, const Vec3& wi, float& pdf) const {
  const Vec3 woL = frame_.toLocal(wo), wiL = frame_.toLocal(wi);
  const float sEo = sheenMax_ * sheen_->albedo(woL.z), sEi = sheenMax_ * sheen_->albedo(wiL.z);
  const float ps = sheenProbability(sEo);
  float basePdf;
  const Color base = baseEval(wo, wi, basePdf);
  const float sheenPdf = sameHemisphere(woL, wiL) ? cosineHemispherePdf(absCosTheta(wiL)) : 0.0f;
  pdf = ps * sheenPdf + (1.0f - ps) * basePdf;
  const Color sheen =
      includes(kDiffuseLobes) ? sheenColor_.value * sheen_->eval(woL, wiL) : Color(0.0f);
  return sheen + base * std::min(1.0f - sEo, 1.0f - sEi);
}

BsdfSample Bsdf::sheenSample(const Vec3& wo, float uc, Vec2 u) const {
  const Vec3 woL = frame_.toLocal(wo);
  const float sEo = sheenMax_ * sheen_->albedo(woL.z), ps = sheenProbability(sEo);
  BsdfSample s;
  if (uc < ps) {  // the sheen lobe is broad: cosine-weighted directions on wo's side
    if (woL.z == 0) return s;
    Vec3 wi = sampleCosineHemisphere(u);
    wi.z = woL.z < 0 ? -wi.z : wi.z;
    s.wi = frame_.toWorld(wi);
  } else {
    const float ucBase = std::min((uc - ps) / (1.0f - ps), 0.99999994f);
    s = baseSample(wo, ucBase, u);
    if (!s.valid()) return s;
    if (s.delta) {
      const float sEi = sheenMax_ * sheen_->albedo(dot(s.wi, frame_.n));
      s.f *= std::min(1.0f - sEo, 1.0f - sEi);
      s.pdf *= 1.0f - ps;
      return s;
    }
  }
  s.f = sheenEval(wo, s.wi, s.pdf);
  if (!(s.pdf > 0) || !std::isfinite(s.pdf)) s.pdf = 0;
  return s;
}

}  // namespace tray
