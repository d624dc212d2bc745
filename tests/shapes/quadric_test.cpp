// Quadrics of revolution and the disk: hit for hit against tessellated twins (fine meshes of
// the same surfaces, through the accelerators), embree against the in-house BVH, intervals of
// the capped solids, uv, and area sampling.
#include "shapes/quadric.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "accel/registry.h"
#include "tests/scene_builder.h"
#include "tests/shapes/solid_meshes.h"

namespace tray {
namespace {

using namespace tray::test;
using Kind = Quadric::Kind;

Ray ray(Vec3 o, Vec3 d) {
  return Ray{o, d, 0.0f, kInfinity};
}

struct Twin {
  std::string name;
  std::shared_ptr<const Shape> shape;
  TriangleMesh mesh;
};

std::vector<Twin> twins() {
  std::vector<Twin> out;
  const int nu = 2048, nv = 128;
  for (bool capped : {false, true}) {
    for (auto [kind, name] :
         {std::pair{Kind::kCylinder, "cylinder"}, std::pair{Kind::kCone, "cone"},
          std::pair{Kind::kParaboloid, "paraboloid"},
          std::pair{Kind::kHyperboloid, "hyperboloid"}}) {
      auto q = std::make_shared<Quadric>(kind, 1.0f, 1.5f, capped, 0.5f);
      out.push_back({name, q, revolvedMesh(*q, nu, kind == Kind::kCylinder ? 1 : nv)});
      if (capped) out.back().name = std::string("capped ") + name;
    }
  }
  // The annulus: two rings in y = 0.
  TriangleMesh disk;
  disk.material = 0;
  for (float rho : {0.3f, 1.0f})
    for (int i = 0; i < nu; ++i) {
      double phi = 2 * M_PI * i / nu;
      disk.positions.push_back({float(rho * std::sin(phi)), 0, float(rho * std::cos(phi))});
    }
  for (int i = 0; i < nu; ++i) {
    uint32_t a = uint32_t(i), b = uint32_t((i + 1) % nu), c = b + uint32_t(nu),
             d = a + uint32_t(nu);
    disk.indices.insert(disk.indices.end(), {a, b, c, a, c, d});
  }
  out.push_back({"disk", std::make_shared<Disk>(1.0f, 0.3f), std::move(disk)});
  return out;
}

TEST(Quadric, HitForHitAgainstTessellatedTwinsOnBothAccelerators) {
  // The mesh's vertices lie on the surface and its chords within 1 - cos(pi / 2048) ~ 1.2e-6
  // (around) and the profile's row sagitta (along y) of it: a ray must hit both or neither,
  // except within that distance of a silhouette or rim, and at nearly the same t.
  std::mt19937 g(9);
  auto u = [&] { return float(g() >> 8) / 16777216.0f; };
  for (const Twin& tw : twins()) {
    Scene a, m;
    addShape(a, tw.shape, Mat4::translate({0.1f, -0.2f, 0.3f}),
             addMaterial(a, diffuse(Color(0.5f))));
    addMaterial(m, diffuse(Color(0.5f)));
    addMeshInstance(m, addMesh(m, tw.mesh), Mat4::translate({0.1f, -0.2f, 0.3f}));
    a.finalize(), m.finalize();
    auto embree = makeAccelerator("embree", a), bvh = makeAccelerator("bvh", a);
    auto mesh = makeAccelerator("embree", m);
    const int n = 20000;
    int hits = 0, disagree = 0, far = 0, accelDiff = 0;
    for (int i = 0; i < n; ++i) {
      Vec3 o{8 * u() - 4, 8 * u() - 4, 8 * u() - 4};
      Vec3 target{2.4f * u() - 1.1f, 1.9f * u() - 0.4f, 2.4f * u() - 0.9f};
      Ray r = ray(o, normalize(target - o));
      Hit ha, hb, hm;
      const bool fa = embree->intersect(r, ha), fb = bvh->intersect(r, hb),
                 fm = mesh->intersect(r, hm);
      accelDiff += fa != fb || (fa && ha.t != hb.t);
      if (fa != fm) {
        ++disagree;
        continue;
      }
      if (!fa) continue;
      ++hits;
      far += std::fabs(ha.t - hm.t) > 1e-3f;
    }
    std::printf(
        "%-20s %d rays, %d hits: %d disagree with the mesh, %d hits farther than 1e-3, "
        "%d embree/bvh differences\n",
        tw.name.c_str(), n, hits, disagree, far, accelDiff);
    EXPECT_GT(hits, n / 10) << tw.name;
    EXPECT_LT(disagree, n / 2000) << tw.name;  // rays within ~1e-5 of a rim or silhouette
    EXPECT_LT(far, n / 2000) << tw.name;       // grazing hits, where t is ill-conditioned
    EXPECT_EQ(accelDiff, 0) << tw.name;
  }
}

TEST(Quadric, CappedSolidsHaveIntervalsAndOpenSurfacesNone) {
  Quadric cyl(Kind::kCylinder, 1.0f, 2.0f, true), open(Kind::kCylinder, 1.0f, 2.0f, false);
  std::vector<Interval> iv;
  cyl.intervals(ray({0, -5, 0.5f}, {0, 1, 0}), iv);  // through both caps
  ASSERT_EQ(iv.size(), 1u);
  EXPECT_NEAR(iv[0].enter.t, 5.0f, 1e-6f);
  EXPECT_NEAR(iv[0].exit.t, 7.0f, 1e-6f);
  EXPECT_EQ(iv[0].enter.normal.y, -1.0f);
  EXPECT_EQ(iv[0].exit.normal.y, 1.0f);
  iv.clear();
  cyl.intervals(ray({-5, 1, 0}, {1, 0, 0}), iv);  // through the side
  ASSERT_EQ(iv.size(), 1u);
  EXPECT_NEAR(iv[0].enter.t, 4.0f, 1e-6f);
  EXPECT_LT(iv[0].enter.normal.x, 0.0f);
  iv.clear();
  open.intervals(ray({-5, 1, 0}, {1, 0, 0}), iv);
  EXPECT_TRUE(iv.empty());
  EXPECT_FALSE(open.isSolid());
  EXPECT_TRUE(cyl.isSolid());
  Hit h;  // open: the axis ray passes through
  EXPECT_FALSE(open.intersect(ray({0, -5, 0.5f}, {0, 1, 0}), h));
  ASSERT_TRUE(open.intersect(ray({0, 1, 0}, {1, 0, 0}), h));  // from inside: the wall
  EXPECT_NEAR(h.t, 1.0f, 1e-6f);
  // A double cone (hyperboloid of waist 0) capped: two cones meeting at the apex; a ray along
  // the axis crosses cap, apex, cap: one interval.
  Quadric dc(Kind::kHyperboloid, 1.0f, 2.0f, true, 0.0f);
  iv.clear();
  dc.intervals(ray({0.5f, 1, -5}, {0, 0, 1}), iv);  // at y = 1 (the apex plane): misses
  EXPECT_TRUE(iv.empty());
  iv.clear();
  dc.intervals(ray({-5, 0.1f, 0}, {1, 0, 0}), iv);  // near the bottom cap: one chord
  ASSERT_EQ(iv.size(), 1u);
  EXPECT_NEAR(iv[0].exit.t - iv[0].enter.t, 2 * 0.9f, 1e-5f);
}

TEST(Quadric, UvOnSideAndCaps) {
  Quadric cyl(Kind::kCylinder, 2.0f, 4.0f, true);
  Hit h;
  ASSERT_TRUE(cyl.intersect(ray({5, 1, 0}, {-1, 0, 0}), h));
  EXPECT_NEAR(h.uv.x, 0.25f, 1e-6f);
  EXPECT_NEAR(h.uv.y, 0.25f, 1e-6f);
  ASSERT_TRUE(cyl.intersect(ray({0, 9, 1}, {0, -1, 0}), h));  // top cap, half way out
  EXPECT_NEAR(h.uv.y, 0.5f, 1e-6f);
  Vec3 dpdu, dpdv;
  const Vec3 p(0.6f, 1.0f, 0.8f);  // on the paraboloid rho^2 = y (r = 1, h = 1)
  Quadric par(Kind::kParaboloid, 1.0f, 1.0f, false);
  par.uvDerivatives(p, par.sideNormal(p), dpdu, dpdv);
  EXPECT_NEAR(dot(dpdv, par.sideNormal(p)), 0.0f, 1e-5f);  // tangent
  EXPECT_NEAR(dpdv.y, 1.0f, 1e-6f);
}

TEST(Quadric, AreaSamplingIsUniformOverSideAndCaps) {
  const Transform toWorld(Mat4::translate({1, 0, 0}) * Mat4::scale(Vec3(2.0f)));
  std::mt19937 g(4);
  auto u = [&] { return float(g() >> 8) / 16777216.0f; };
  struct Case {
    std::shared_ptr<const Shape> s;
    float area;     // object space
    float capFrac;  // expected fraction of samples on caps (n = +-y)
  };
  const float kR = 0.5f, kH = 2.0f, slant = std::sqrt(kR * kR + kH * kH);
  const Case cases[] = {
      {std::make_shared<Quadric>(Kind::kCylinder, kR, kH, true),
       2 * kPi * kR * kH + 2 * kPi * kR * kR, 2 * kR / (2 * kH + 2 * kR)},
      {std::make_shared<Quadric>(Kind::kCylinder, kR, kH, false), 2 * kPi * kR * kH, 0},
      {std::make_shared<Quadric>(Kind::kCone, kR, kH, true), kPi * kR * slant + kPi * kR * kR,
       kR / (slant + kR)},
      {std::make_shared<Disk>(kR, 0.2f), kPi * (kR * kR - 0.04f), 1},
  };
  for (const Case& c : cases) {
    EXPECT_NEAR(c.s->area(toWorld), 4 * c.area, 1e-4f);
    const int n = 100000;
    int caps = 0, upperHalf = 0;
    for (int i = 0; i < n; ++i) {
      auto s = c.s->sampleArea(toWorld, {u(), u()});
      ASSERT_TRUE(s);
      EXPECT_FLOAT_EQ(s->pdf, 1 / c.s->area(toWorld));
      const Vec3 p = toWorld.inversePoint(s->p);
      caps += std::fabs(s->n.y) > 0.99999f;
      upperHalf += p.y > 0.5f * kH;
    }
    const double f = double(caps) / n;
    EXPECT_NEAR(f, c.capFrac, 4 * std::sqrt(c.capFrac * (1 - c.capFrac) / n) + 1e-9);
    if (c.capFrac == 0) {
      EXPECT_NEAR(double(upperHalf) / n, 0.5, 0.01);  // y uniform on the side
    }
  }
  // The cone's side holds 1/4 of its area above half height (rho halves there).
  Quadric cone(Kind::kCone, kR, kH, false);
  int upper = 0;
  for (int i = 0; i < 100000; ++i)
    upper += toWorld.inversePoint(cone.sampleArea(toWorld, {u(), u()})->p).y > 0.5f * kH;
  EXPECT_NEAR(upper / 1e5, 0.25, 0.01);
  // Paraboloid and hyperboloid are not sampled.
  EXPECT_EQ(Quadric(Kind::kParaboloid, 1, 1, true).area(toWorld), 0.0f);
}

}  // namespace
}  // namespace tray
