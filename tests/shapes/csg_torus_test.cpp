// CSG with tori and capped quadrics, traced through Scene + both accelerators (embree, bvh) and
// checked ray by ray against a point-membership oracle, as csg_oracle_test.cpp does for boxes
// and spheres: the solid's signed-distance bound f (exact per primitive: torus, box, sphere,
// capped cylinder; min / max / max(a, -b) for union / intersection / difference), evaluated in
// double. f is 1-Lipschitz, so the oracle marches each ray by |f| (at least kMinStep) and
// finds the first point robustly inside (f < -kEps) without skipping any:
//   leak:    a robustly inside point before the renderer's hit (or no hit);
//   phantom: the hit lies off the boundary, |f(hit)| > kEps.
// Rays: from 24 eyes around each solid, aimed at random points of its bounds, and grazing
// rays tangent to the torus at 1e-3 .. 1e-6 of its tube radius either side.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "accel/registry.h"
#include "core/error.h"
#include "shapes/csg.h"
#include "shapes/quadric.h"
#include "shapes/torus.h"
#include "tests/double_vec3.h"
#include "tests/scene_builder.h"

namespace tray {
namespace {

using namespace tray::test;

constexpr double kEps = 1e-5, kMinStep = 1e-6;

using P3 = DVec3;

// Exact signed distances (object space; placements below are translations only).
double torusSd(P3 p, double R, double r) {
  return std::hypot(std::hypot(p.x, p.z) - R, p.y) - r;
}
double sphereSd(P3 p, double r) {
  return len(p) - r;
}
double boxSd(P3 p, P3 lo, P3 hi) {
  P3 c = 0.5 * (lo + hi), h = 0.5 * (hi - lo);
  P3 q{std::fabs(p.x - c.x) - h.x, std::fabs(p.y - c.y) - h.y, std::fabs(p.z - c.z) - h.z};
  P3 o{std::max(q.x, 0.0), std::max(q.y, 0.0), std::max(q.z, 0.0)};
  return len(o) + std::min(std::max(q.x, std::max(q.y, q.z)), 0.0);
}
double cylinderSd(P3 p, double r, double h) {  // capped, y in [0, h]
  double a = std::hypot(p.x, p.z) - r, b = std::fabs(p.y - 0.5 * h) - 0.5 * h;
  return std::hypot(std::max(a, 0.0), std::max(b, 0.0)) + std::min(std::max(a, b), 0.0);
}

struct Solid {
  const char* name;
  std::shared_ptr<const Shape> shape;
  double (*f)(P3);
  double R, r;  ///< the torus in it, for grazing rays (centred at the origin)
};

CsgChild child(std::shared_ptr<const Shape> s, const Mat4& m = Mat4::identity()) {
  return {std::move(s), Transform(m), -1, "child"};
}

std::vector<Solid> solids(QuarticSolver solver) {
  auto torus = [solver](float R, float r) { return std::make_shared<Torus>(R, r, solver); };
  return {
      {"torus minus box",
       std::make_shared<Csg>(
           CsgOp::kDifference,
           std::vector<CsgChild>{child(torus(1, 0.3f)),
                                 child(std::make_shared<Box>(Vec3(0, -1, -2), Vec3(2, 1, 2)))}),
       [](P3 p) { return std::max(torusSd(p, 1, 0.3), -boxSd(p, {0, -1, -2}, {2, 1, 2})); }, 1,
       0.3},
      {"torus and sphere",
       std::make_shared<Csg>(
           CsgOp::kIntersection,
           std::vector<CsgChild>{child(torus(1, 0.4f)), child(std::make_shared<Sphere>(1.0f),
                                                              Mat4::translate({1, 0.2f, 0}))}),
       [](P3 p) { return std::max(torusSd(p, 1, 0.4), sphereSd(p - P3{1, 0.2, 0}, 1)); }, 1, 0.4},
      {"thin torus union sphere",
       std::make_shared<Csg>(
           CsgOp::kUnion,
           std::vector<CsgChild>{child(torus(1, 0.01f)), child(std::make_shared<Sphere>(0.5f))}),
       [](P3 p) { return std::min(torusSd(p, 1, 0.01), sphereSd(p, 0.5)); }, 1, 0.01},
      {"capped cylinder minus torus",
       std::make_shared<Csg>(
           CsgOp::kDifference,
           std::vector<CsgChild>{
               child(std::make_shared<Quadric>(Quadric::Kind::kCylinder, 1.0f, 1.0f, true),
                     Mat4::translate({0, -0.5f, 0})),
               child(torus(1, 0.25f))}),
       [](P3 p) { return std::max(cylinderSd(p - P3{0, -0.5, 0}, 1, 1), -torusSd(p, 1, 0.25)); }, 1,
       0.25},
  };
}

struct Tally {
  long rays = 0, mustHit = 0, leaks = 0, phantoms = 0;
};

void checkRay(const Solid& s, const std::vector<const Accelerator*>& accels, const Ray& ray,
              Tally& t) {
  const P3 o{ray.o.x, ray.o.y, ray.o.z}, d{ray.d.x, ray.d.y, ray.d.z};
  const double dl = len(d);
  // The first robustly inside point, marching by the distance bound.
  double tInside = -1;
  for (double x = 0, steps = 0; x * dl < 20 && steps < 1e6; ++steps) {
    const double v = s.f(o + x * d);
    if (v < -kEps) {
      tInside = x;
      break;
    }
    x += std::max(std::fabs(v), kMinStep) / dl;
  }
  for (const Accelerator* a : accels) {
    ++t.rays;
    t.mustHit += tInside >= 0;
    Hit hit;
    const bool found = a->intersect(ray, hit);
    if (tInside >= 0 && (!found || hit.t > tInside + kEps / dl)) {
      ++t.leaks;
      continue;
    }
    if (found && std::fabs(s.f(o + double(hit.t) * d)) > kEps) ++t.phantoms;
  }
}

/// Leaks and phantom hits over all solids; with `expectClean`, each must be zero.
Tally checkSolids(QuarticSolver solver, bool expectClean) {
  Tally all;
  for (const Solid& s : solids(solver)) {
    Scene scene;
    addShape(scene, s.shape, Mat4::identity(), addMaterial(scene, diffuse(Color(0.8f))));
    scene.finalize();
    auto embree = makeAccelerator("embree", scene), bvh = makeAccelerator("bvh", scene);
    const std::vector<const Accelerator*> accels{embree.get(), bvh.get()};
    std::mt19937_64 g(17);
    auto u = [&] { return double(g() >> 11) * (1.0 / 9007199254740992.0); };
    Tally random, grazing;
    for (int i = 0; i < 24 * 400; ++i) {
      double z = 2 * u() - 1, phi = 2 * M_PI * u(), sn = std::sqrt(1 - z * z);
      P3 eye = 4.0 * P3{sn * std::cos(phi), z, sn * std::sin(phi)};
      P3 target{2.6 * u() - 1.3, 1.2 * u() - 0.6, 2.6 * u() - 1.3};
      P3 d = target - eye;
      checkRay(
          s, accels,
          Ray{{float(eye.x), float(eye.y), float(eye.z)}, {float(d.x), float(d.y), float(d.z)}},
          random);
    }
    for (int i = 0; i < 4000; ++i) {  // tangent to the torus' tube, offset along its normal
      double phi = 2 * M_PI * u(), th = 2 * M_PI * u();
      P3 n{std::cos(th) * std::sin(phi), std::sin(th), std::cos(th) * std::cos(phi)};
      P3 p = P3{s.R * std::sin(phi), 0, s.R * std::cos(phi)} + s.r * n;
      P3 w{2 * u() - 1, 2 * u() - 1, 2 * u() - 1}, tan = w - dot(w, n) * n;
      tan = (1 / len(tan)) * tan;
      double off = s.r * std::pow(10.0, -3 - 3 * u()) * (u() < 0.5 ? -1 : 1);
      P3 o = p + off * n - 3.0 * tan;
      checkRay(
          s, accels,
          Ray{{float(o.x), float(o.y), float(o.z)}, {float(tan.x), float(tan.y), float(tan.z)}},
          grazing);
    }
    for (const auto& [what, t] : {std::pair{"random", random}, std::pair{"grazing", grazing}}) {
      std::printf("%-28s %-8s %6ld rays (%6ld must hit): %ld leaks, %ld phantom hits\n", s.name,
                  what, t.rays, t.mustHit, t.leaks, t.phantoms);
      EXPECT_GT(t.mustHit, t.rays / 20) << s.name;
      all.leaks += t.leaks, all.phantoms += t.phantoms, all.rays += t.rays;
      if (!expectClean) continue;
      EXPECT_EQ(t.leaks, 0) << s.name << " " << what;
      EXPECT_EQ(t.phantoms, 0) << s.name << " " << what;
    }
  }
  return all;
}

TEST(CsgTorus, NoLeaksNoPhantomsOnEitherAccelerator) {
  checkSolids(QuarticSolver::kIsolated, true);
}

TEST(CsgTorus, WithTheClosedFormSolverTheSameChecksFail) {
  // The same rays and checks catch the closed form's lost and invented roots.
  const Tally t = checkSolids(QuarticSolver::kClosedForm, false);
  EXPECT_GT(t.leaks + t.phantoms, 10);
}

TEST(CsgTorus, OpenSurfacesAreRefusedAsOperands) {
  try {
    Csg c(CsgOp::kDifference,
          {child(std::make_shared<Torus>()),
           {std::make_shared<Quadric>(Quadric::Kind::kCylinder, 1.0f, 1.0f, false), Transform(), -1,
            "tube"}},
          "cut");
    FAIL() << "an open cylinder was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'tube' that is an open surface"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(Csg(CsgOp::kUnion, {child(std::make_shared<Disk>())}), Error);
  EXPECT_NO_THROW(Csg(CsgOp::kUnion,
                      {child(std::make_shared<Quadric>(Quadric::Kind::kCone, 1.0f, 1.0f, true))}));
}

}  // namespace
}  // namespace tray
