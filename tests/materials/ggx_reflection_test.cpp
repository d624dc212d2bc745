#include "materials/ggx_reflection.h"

#include <gtest/gtest.h>

#include "tests/materials/chi2.h"

namespace tray {
namespace {

TEST(Ggx, DistributionIsNormalisedInProjectedArea) {
  // Integral of D(m) cos(theta_m) over the hemisphere = 1 (Walter et al. 2007, eq. 4).
  for (float alpha : {0.1f, 0.4f, 1.0f}) {
    GgxDistribution d(alpha);
    double sum = 0;
    const int nt = 4000, np = 8;
    for (int i = 0; i < nt; ++i)
      for (int j = 0; j < np; ++j) {
        double t = (i + 0.5) / nt * kPi / 2, p = (j + 0.5) / np * 2 * kPi;
        Vec3 m(float(std::sin(t) * std::cos(p)), float(std::sin(t) * std::sin(p)),
               float(std::cos(t)));
        sum += d.D(m) * std::cos(t) * std::sin(t) * (kPi / 2 / nt) * (2 * kPi / np);
      }
    EXPECT_NEAR(sum, 1.0, 2e-3) << alpha;
  }
}

TEST(Ggx, VisibleNormalSamplingMatchesItsDensity) {
  // Heitz 2018: sampled microfacet normals follow D_wo(m) = G1(wo) max(0, wo.m) D(m) / cos_o.
  for (float alpha : {0.2f, 0.6f})
    for (float theta : {0.2f, 1.2f}) {
      GgxDistribution d(alpha);
      Vec3 wo(std::sin(theta), 0, std::cos(theta));
      auto sample = [&](Vec2 u, float, Vec3& m) {
        m = d.sampleVisibleNormal(wo, u);
        return true;
      };
      auto pdf = [&](const Vec3& m) { return dot(wo, m) > 0 ? d.visibleD(wo, m) : 0.0f; };
      test::Chi2Result r = test::chi2Test(sample, pdf, 200000, 5);
      EXPECT_GT(r.pValue, 0.01 / 4) << alpha << " " << theta << " chi2 " << r.statistic;
      EXPECT_NEAR(r.pdfIntegral, 1.0, 0.01);
    }
}

TEST(GgxReflection, WhiteMetalLosesOnlyToMasking) {
  // F = 1: the albedo is the masking-shadowing loss only, <= 1, and near 1 when smooth-ish.
  auto lobe = GgxReflectionLobe::metal(0.05f, Color(1.0f));
  Vec3 wo(0.5f, 0, std::sqrt(0.75f));
  double sum = 0;
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    BsdfSample s = lobe.sample(wo, {(i + 0.5f) / n, (i * 0.618034f) - std::floor(i * 0.618034f)});
    if (s.valid()) sum += s.weight().x;
  }
  EXPECT_LE(sum / n, 1.0 + 1e-3);
  EXPECT_GT(sum / n, 0.97);
}

}  // namespace
}  // namespace tray
