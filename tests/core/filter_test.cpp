#include "core/filter.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "tests/raster_function.h"

namespace tray {
namespace {

using namespace tray::test;

/// Midpoint rule over the support, fine enough for 1e-5 on these smooth profiles.
double integral1D(const Filter& f, double from, double to) {
  const int n = 200000;
  double sum = 0, h = (to - from) / n;
  for (int i = 0; i < n; ++i) sum += f.evaluate1D(float(from + (i + 0.5) * h));
  return sum * h;
}

TEST(Filter, RadiiAndProfilesIntegrateToTheirClosedForms) {
  const double s = Filter::kGaussianSigma, r = 1.5;
  const double gauss = std::sqrt(2 * M_PI) * s * std::erf(r / (std::sqrt(2.0) * s)) -
                       2 * r * std::exp(-r * r / (2 * s * s));
  const struct {
    const char* name;
    double radius, integral;
  } cases[] = {
      {"box", 0.5, 1.0}, {"tent", 1.0, 1.0}, {"gaussian", 1.5, gauss}, {"mitchell", 2.0, 1.0}};
  for (const auto& c : cases) {
    Filter f = Filter::make(c.name);
    EXPECT_EQ(f.radius(), float(c.radius)) << c.name;
    EXPECT_NEAR(integral1D(f, -c.radius, c.radius), c.integral, 1e-5) << c.name;
    EXPECT_EQ(f.evaluate1D(float(c.radius) + 1e-3f), 0.0f) << c.name;
    EXPECT_GT(f.evaluate1D(0), 0.0f) << c.name;
  }
  // Mitchell B = C = 1/3: value 8/9 at 0, negative lobe between 1 and 2.
  Filter m = Filter::make("mitchell");
  EXPECT_NEAR(m.evaluate1D(0), 8.0 / 9.0, 1e-6);
  EXPECT_LT(m.evaluate1D(1.5f), 0.0f);
  EXPECT_NEAR(m.evaluate({0.5f, -0.25f}), m.evaluate1D(0.5f) * m.evaluate1D(0.25f), 1e-7);
  EXPECT_THROW(Filter::make("lanczos"), Error);
}

/// Renders one pixel of a raster image with the default renderPixel.
PixelValue renderOne(const RasterImage& image, const std::string& filter,
                     const std::string& pattern, int spp, int x = 4, int y = 4) {
  RasterWorld world;
  RenderSettings s;
  s.set("filter", filter), s.set("pixel-sampler", pattern), s.set("spp", spp);
  RasterIntegrator integrator(world.context(s, 9, 9), image);
  RayStats stats;
  PixelValue v = integrator.renderPixel(x, y, stats);
  EXPECT_EQ(stats.cameraRays, v.samples);
  return v;
}

TEST(Filter, ConstantImageStaysConstant) {
  RasterImage constant{[](float, float) { return 0.37f; }};
  for (const auto& name : Filter::names())
    for (const char* pattern : {"center", "corners", "grid", "jitter"}) {
      PixelValue v = renderOne(constant, name, pattern, 25);
      EXPECT_NEAR(v.radiance.x, 0.37f, 1e-6f) << name << " " << pattern;
      EXPECT_NEAR(v.alpha, 1.0f, 1e-6f) << name << " " << pattern;
    }
}

TEST(Filter, EdgeIsSmoothedByTheFilterProfile) {
  // A vertical step at raster x = 4.5 + e, seen by pixel 4 (centre 4.5): the filtered value is
  // the share of the 1D profile beyond e.
  for (const auto& name : Filter::names()) {
    Filter f = Filter::make(name);
    for (float e : {-0.3f, 0.0f, 0.2f, 0.7f, 1.2f}) {
      RasterImage step{[e](float x, float) { return x > 4.5f + e ? 1.0f : 0.0f; }};
      const double expected = integral1D(f, std::min<double>(e, f.radius()), f.radius()) /
                              integral1D(f, -f.radius(), f.radius());
      // 64 x 64 grid: each column of samples is 2r/64 wide, the step quantised to it.
      const double tolerance = 2 * f.radius() / 64 * f.evaluate1D(0) * 1.5 + 1e-4;
      PixelValue v = renderOne(step, name, "grid", 64 * 64);
      EXPECT_NEAR(v.radiance.x, expected, tolerance) << name << " edge at " << e;
    }
  }
  // Box: exact coverage. Tent: (1 - e)^2 / 2 beyond e; it reaches past the pixel (e = 0.7)
  // where the box sees nothing: that is the smoothing.
  RasterImage step07{[](float x, float) { return x > 5.2f ? 1.0f : 0.0f; }};
  EXPECT_EQ(renderOne(step07, "box", "grid", 256).radiance.x, 0.0f);
  // Tolerance: one sample column (1/32 px) at tent height 0.3.
  EXPECT_NEAR(renderOne(step07, "tent", "grid", 4096).radiance.x, 0.09f / 2, 0.3f / 32);
  RasterImage step02{[](float x, float) { return x > 4.7f ? 1.0f : 0.0f; }};
  EXPECT_NEAR(renderOne(step02, "box", "grid", 4096).radiance.x, 0.3f, 1.0f / 64 + 1e-6f);
}

}  // namespace
}  // namespace tray
