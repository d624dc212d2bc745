// Emissive rectangles (lights/rectangle_light_lanes.h, core/spherical_rectangle_lanes.h:
// Urena et al. 2013) and their detection in meshes (lights/quad_lights.h): the solid angle
// against two spherical triangles, the inverse map against the forward one, a chi-square test
// of AreaLight::sample against AreaLight::pdf in every mode for rectangles far, near, grazing
// and small, the pdf integrating to 1 over the rectangle, and a LightSet whose quad is one
// rectangle giving a BSDF-sampled hit on either triangle the pdf its light sample has there.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "core/spherical_triangle_lanes.h"
#include "lights/area_light.h"
#include "lights/light_set.h"
#include "lights/quad_lights.h"
#include "tests/materials/chi2.h"
#include "tests/scene_builder.h"

namespace tray {
namespace {

struct Case {
  const char* name;
  Vec3 corner, ex, ey, ref;
};

// Receivers at the origin but for the near one; rectangles emit both ways (double-sided).
// "edge-on" (under 1.8 degrees of elevation, under 0.1 sr) is sampled by area in every mode
// (preciseRectangleSolidAngle), and so is "grazing" (0.098 sr), whose precision the direct
// tests of the parametrization below still check.
const Case kCases[] = {
    {"far", {-0.5f, 2, -0.3f}, {1.1f, 0, 0.1f}, {-0.1f, 0, 1.1f}, {0, 0, 0}},
    {"near-large", {-3, 0, -2}, {6, 0, 0}, {0, 0, 6}, {0.1f, -0.05f, 0.3f}},
    {"grazing", {0.3f, 0.02f, -1}, {1.7f, 0, 0}, {0, 0, 2.5f}, {0, 0, 0}},
    {"edge-on", {-1, 0.03f, -3.0f}, {2, 0, 0}, {0, 0, -0.8f}, {0, 0, 0}},
    {"low", {0.3f, 0.12f, -1}, {1.7f, 0, 0}, {0, 0, 2.5f}, {0, 0, 0}},  // 3 to 20 degrees up
    {"side", {0.5f, -1, 1}, {0, 2, 0}, {0, 0, 0.7f}, {0, 0, 0}},
    {"small", {-0.05f, 3, 0}, {0.1f, 0, 0}, {0, 0, 0.08f}, {0, 0, 0}},  // ~9e-4 sr
};

const char* modeName(TriangleSampling m) {
  return m == TriangleSampling::kArea ? "area" : m == TriangleSampling::kAuto ? "auto" : "solid";
}

constexpr int kBins = 24;  // the rectangle's parameters (s, t) binned: equal areas

/// Where the light samples by solid angle at all (not "edge-on", whose 1e-4 imprecision
/// preciseRectangleSolidAngle avoids).
bool sphericalCase(const Case& c) {
  return std::string(c.name) != "edge-on";
}

TEST(RectangleSampling, SolidAngleIsTwoSphericalTriangles) {
  for (const Case& c : kCases) {
    if (!sphericalCase(c)) continue;
    const Vec3 s = c.corner - c.ref;
    const float rect = sphericalRectangleOf(s, c.ex, c.ey).area;
    const float tris = sphericalTriangleOf(s, s + c.ex, s + c.ex + c.ey).area +
                       sphericalTriangleOf(s, s + c.ex + c.ey, s + c.ey).area;
    EXPECT_NEAR(rect / tris, 1.0f, 1e-4f) << c.name << " " << tris;
  }
}

TEST(RectangleSampling, InverseUndoesTheSample) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  for (const Case& c : kCases) {
    if (!sphericalCase(c)) continue;
    const Vec3 s = c.corner - c.ref;
    const SphericalRectangleOf<Vec3> r = sphericalRectangleOf(s, c.ex, c.ey);
    for (int i = 0; i < 2000; ++i) {
      const Vec2 u{u01(rng), u01(rng)};
      const Vec2 q = sampleSphericalRectangle(r, u);
      const Vec2 back = invertSphericalRectangleSample(r, q.x * r.x + q.y * r.y + r.z0 * r.z);
      EXPECT_NEAR(back.x, u.x, 2e-3f) << c.name;
      EXPECT_NEAR(back.y, u.y, 2e-3f) << c.name;
    }
  }
}

void checkCase(const Case& c, TriangleSampling mode) {
  SCOPED_TRACE(std::string(c.name) + " " + modeName(mode));
  const Vec3 n = normalize(cross(c.ex, c.ey));
  const AreaLight light = AreaLight::rectangle(c.corner, c.ex, c.ey, n, Color(1.0f), true, mode);
  const LightSampleContext ctx{c.ref, normalize(Vec3(0.3f, 1, -0.2f)), true, true};
  std::vector<double> observed(kBins * kBins, 0.0), expected(observed.size(), 0.0);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  const int samples = 200000;
  const double ex2 = dot(c.ex, c.ex), ey2 = dot(c.ey, c.ey);
  for (int i = 0; i < samples; ++i) {
    const LightSample s = light.sample(ctx, Vec2{u01(rng), u01(rng)});
    ASSERT_TRUE(s.valid());
    const Vec3 d = s.p - c.corner;
    const int bi = std::clamp(int(dot(d, c.ex) / ex2 * kBins), 0, kBins - 1);
    const int bj = std::clamp(int(dot(d, c.ey) / ey2 * kBins), 0, kBins - 1);
    observed[size_t(bi * kBins + bj)] += 1;
    ASSERT_NEAR(light.pdf(ctx, s.wi, s.p, n) / s.pdf, 1.0f, 2e-3f) << i;
  }
  const int sub = 24;
  double integral = 0;
  const double dA = double(light.area()) / (kBins * sub * kBins * sub);
  for (int i = 0; i < kBins * sub; ++i)
    for (int j = 0; j < kBins * sub; ++j) {
      const float a = float((i + 0.5) / (kBins * sub)), b = float((j + 0.5) / (kBins * sub));
      const Vec3 p = c.corner + a * c.ex + b * c.ey, d = p - c.ref;
      const double dist2 = dot(d, d);
      const Vec3 w = d / std::sqrt(float(dist2));
      const double mass = double(light.pdf(ctx, w, p, n)) * std::fabs(dot(n, w)) / dist2 * dA;
      expected[size_t((i / sub) * kBins + j / sub)] += mass * samples;
      integral += mass;
    }
  EXPECT_NEAR(integral, 1.0, 3e-3);
  double chi2 = 0;
  int dof = -1;
  for (size_t b = 0; b < observed.size(); ++b)
    if (expected[b] >= 5)
      chi2 += (observed[b] - expected[b]) * (observed[b] - expected[b]) / expected[b], ++dof;
  const double p = test::gammaQ(dof / 2.0, chi2 / 2.0);
  std::printf("%-10s %-5s solid angle %.3g sr: chi2 %.1f, dof %d, p %.3f, integral %.5f\n", c.name,
              modeName(mode), double(sphericalRectangleOf(c.corner - c.ref, c.ex, c.ey).area), chi2,
              dof, p, integral);
  EXPECT_GT(dof, 100);
  EXPECT_GT(p, 1e-3) << "chi2 " << chi2 << " dof " << dof;
}

TEST(RectangleSampling, EveryModeSamplesItsOwnPdfChiSquare) {
  for (const Case& c : kCases)
    for (TriangleSampling m :
         {TriangleSampling::kArea, TriangleSampling::kSolidAngle, TriangleSampling::kAuto})
      checkCase(c, m);
}

TEST(RectangleSampling, SolidAnglePdfIsOneOverTheSolidAngle) {
  // No normal at the receiver: no warp, so the pdf is 1 / the solid angle where chosen.
  for (const Case& c : kCases) {
    // Under 1.8 degrees and 0.1 sr: by area (preciseRectangleSolidAngle).
    if (!sphericalCase(c) || std::string(c.name) == "grazing") continue;
    const Vec3 n = normalize(cross(c.ex, c.ey));
    const float omega = sphericalRectangleOf(c.corner - c.ref, c.ex, c.ey).area;
    const LightSampleContext ctx{c.ref, Vec3(0, 0, 0), true, true};
    const Vec3 p = c.corner + 0.3f * c.ex + 0.6f * c.ey;
    const float pdf =
        AreaLight::rectangle(c.corner, c.ex, c.ey, n, Color(1.0f), true, TriangleSampling::kAuto)
            .pdf(ctx, normalize(p - c.ref), p, n);
    EXPECT_FLOAT_EQ(pdf, 1.0f / omega) << c.name;
  }
}

TriangleMesh twoTriangles(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  TriangleMesh m;  // a b c and c b d: the shared edge b c, vertices split as glTF often has
  m.positions = {a, b, c, c, b, d};
  m.indices = {0, 1, 2, 3, 4, 5};
  return m;
}

TEST(RectangleSampling, FindsRectanglesNotParallelograms) {
  const Transform id{Mat4::identity()};
  // A rectangle 2 x 1 in z = 0, both triangles wound the same way (front +z).
  const auto rect =
      findMeshRectangles(twoTriangles({0, 0, 0}, {2, 0, 0}, {0, 1, 0}, {2, 1, 0}), id);
  ASSERT_EQ(rect.size(), 1u);
  EXPECT_FLOAT_EQ(length(cross(rect[0].ex, rect[0].ey)), 2.0f);
  EXPECT_NEAR(dot(rect[0].ex, rect[0].ey), 0.0f, 1e-6f);
  // Within the tolerance (1e-4): a corner off by 1e-6.
  EXPECT_EQ(findMeshRectangles(twoTriangles({0, 0, 0}, {2, 0, 0}, {0, 1, 0}, {2, 1.000001f, 0}), id)
                .size(),
            1u);
  // A parallelogram that is no rectangle; a kite; triangles facing opposite ways.
  EXPECT_TRUE(findMeshRectangles(twoTriangles({0, 0, 0}, {2, 0, 0}, {0.5f, 1, 0}, {2.5f, 1, 0}), id)
                  .empty());
  EXPECT_TRUE(findMeshRectangles(twoTriangles({0, 0, 0}, {2, 0, 0}, {0, 1, 0}, {2.5f, 1.5f, 0}), id)
                  .empty());
  TriangleMesh flipped = twoTriangles({0, 0, 0}, {2, 0, 0}, {0, 1, 0}, {2, 1, 0});
  std::swap(flipped.indices[4], flipped.indices[5]);
  EXPECT_TRUE(findMeshRectangles(flipped, id).empty());
  // A shear in world space unmakes it.
  Mat4 shear = Mat4::identity();
  shear.m[0][1] = 0.5f;
  EXPECT_TRUE(
      findMeshRectangles(twoTriangles({0, 0, 0}, {2, 0, 0}, {0, 1, 0}, {2, 1, 0}), Transform(shear))
          .empty());
}

TEST(RectangleSampling, BsdfHitOnEitherTrianglePdfEqualsTheLightSample) {
  // A scene whose emitter is one quad: with --triangle-sampling auto and solid-angle it is one
  // rectangle; a direction toward either triangle gets LightSet::pdf of the light lightAt
  // names, which must be the pdf LightSet::sample gave the same point (MIS consistency), and
  // area mode keeps two triangles.
  Scene scene;
  Material emitter = test::diffuse(Color(0.0f));
  emitter.emissive = Color(4.0f);
  const int glow = test::addMaterial(scene, emitter);
  TriangleMesh quad = twoTriangles({-1, 2, -0.5f}, {1, 2, -0.5f}, {-1, 2, 0.5f}, {1, 2, 0.5f});
  quad.material = glow;
  test::addMeshInstance(scene, test::addMesh(scene, std::move(quad)), Mat4::identity());
  scene.finalize();
  const LightSet area(scene, LightSamplerKind::kBvh, TriangleSampling::kArea);
  EXPECT_EQ(area.rectangleCount(), 0u);
  for (TriangleSampling mode : {TriangleSampling::kAuto, TriangleSampling::kSolidAngle}) {
    const LightSet lights(scene, LightSamplerKind::kBvh, mode);
    ASSERT_EQ(lights.rectangleCount(), 1u);
    EXPECT_EQ(lights.lightAt(0, 0), lights.lightAt(0, 1));
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<float> u01(0.0f, 1.0f);
    int hits[2] = {0, 0};
    for (int i = 0; i < 4000; ++i) {
      const Vec3 ref(4 * u01(rng) - 2, 1.8f * u01(rng) - 0.5f, 4 * u01(rng) - 2);
      const LightSampleContext ctx{ref, normalize(Vec3(u01(rng) - 0.5f, 1, u01(rng) - 0.5f)), true,
                                   true};
      const LightSample s = lights.sample(ctx, u01(rng), Vec2{u01(rng), u01(rng)});
      if (!s.valid()) continue;
      // The triangle the point lies on: a b c where its (x, z) parameters sum to at most 1.
      const float bx = (s.p.x + 1) / 2, bz = s.p.z + 0.5f;
      const uint32_t t = bx + bz <= 1.0f ? 0u : 1u;
      ++hits[t];
      const int index = lights.lightAt(0, t);
      const float pdf = lights.pdf(index, ctx, s.wi, s.p, Vec3(0, -1, 0));
      ASSERT_NEAR(pdf / s.pdf, 1.0f, 2e-3f) << modeName(mode) << " " << i;
    }
    EXPECT_GT(hits[0], 1000);
    EXPECT_GT(hits[1], 1000);
  }
}

}  // namespace
}  // namespace tray
