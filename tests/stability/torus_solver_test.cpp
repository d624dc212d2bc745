// Stability: ray-torus roots. Random rays (general, grazing the tube at 1e-1 .. 1e-7 of its
// radius on both sides, from far away, from inside) against a fat (r/R = 0.25) and a thin
// (r/R = 0.01) torus, each ray's crossings compared with an independent long-double reference
// (tests/shapes/torus_reference.h). The closed-form Ferrari / Cardano solution loses and invents
// crossings (shown first); the shipped solver (isolation by derivatives, bracketed Newton) has
// none (docs/shapes.md). TRAY_TORUS_RAYS sets the number of rays per torus (default 50000:
// 100k in all); the 1M-ray run of docs/shapes.md is TRAY_TORUS_RAYS=500000.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "shapes/torus.h"
#include "tests/double_vec3.h"
#include "tests/shapes/torus_reference.h"

namespace tray {
namespace {

using test::torusDistance;
using test::torusReference;

struct Rng {
  std::mt19937_64 g;
  explicit Rng(uint64_t seed) : g(seed) {}
  double u() { return double(g() >> 11) * (1.0 / 9007199254740992.0); }
  double range(double a, double b) { return a + (b - a) * u(); }
};

using V = test::DVec3;
Vec3 f3(V a) {
  return {float(a.x), float(a.y), float(a.z)};
}

V randomDir(Rng& rng) {
  double z = rng.range(-1, 1), phi = rng.range(0, 2 * M_PI), s = std::sqrt(1 - z * z);
  return {s * std::cos(phi), z, s * std::sin(phi)};
}

enum Kind { kGeneral, kGrazing, kFar, kInside, kKinds };
const char* kKindNames[] = {"general", "grazing", "far (1e3 R)", "from inside"};

/// A ray of the given kind at the torus (R, r).
Ray makeRay(Kind kind, double R, double r, Rng& rng) {
  const double outer = R + r;
  auto surfacePoint = [&](V& p, V& n) {
    double phi = rng.range(0, 2 * M_PI), th = rng.range(0, 2 * M_PI);
    n = {std::cos(th) * std::sin(phi), std::sin(th), std::cos(th) * std::cos(phi)};
    V c{R * std::sin(phi), 0, R * std::cos(phi)};
    p = c + r * n;
  };
  switch (kind) {
    case kGeneral: {
      V o = rng.range(1.2, 4) * outer * randomDir(rng);
      V target{rng.range(-outer, outer), rng.range(-r, r), rng.range(-outer, outer)};
      return Ray{f3(o), f3(unit(target - o)), -kInfinity, kInfinity};
    }
    case kGrazing: {
      // Tangent to the tube at p, offset along the normal by +-r 10^-k, k in [1, 7].
      V p, n;
      surfacePoint(p, n);
      V t = unit(cross(n, randomDir(rng)));
      double off = r * std::pow(10.0, -rng.range(1, 7)) * (rng.u() < 0.5 ? -1 : 1);
      V o = p + off * n - rng.range(1.5, 3) * outer * t;
      return Ray{f3(o), f3(t), -kInfinity, kInfinity};
    }
    case kFar: {
      V o = 1e3 * outer * randomDir(rng), p, n;
      surfacePoint(p, n);
      p = p - rng.range(0, r) * n;  // a point of the solid near the surface
      return Ray{f3(o), f3(unit(p - o)), -kInfinity, kInfinity};
    }
    default: {
      V p, n;
      surfacePoint(p, n);
      return Ray{f3(p - rng.range(0.01, 0.99) * r * n), f3(randomDir(rng)), -kInfinity, kInfinity};
    }
  }
}

struct Tally {
  long rays = 0, required = 0, lost = 0, phantom = 0, refSteps = 0;
};

/// The rays of one torus with their reference crossings, computed once for all solvers.
struct Case {
  double r;
  std::vector<Ray> rays[kKinds];
  std::vector<test::TorusReference> refs[kKinds];
};

long raysPerTorus() {
  const char* env = std::getenv("TRAY_TORUS_RAYS");
  return env ? std::atol(env) : 50000;
}

const std::vector<Case>& cases() {
  static const std::vector<Case> all = [] {
    std::vector<Case> out;
    for (double r : {0.25, 0.01}) {
      Case c{r, {}, {}};
      Rng rng(r < 0.1 ? 7 : 3);
      const long n = raysPerTorus();
      for (long i = 0; i < n; ++i) {
        const Kind kind = Kind(i % kKinds);
        c.rays[kind].push_back(makeRay(kind, 1.0, r, rng));
        // The torus stores float radii: the reference sees the same numbers.
        c.refs[kind].push_back(torusReference(1.0, double(float(r)), c.rays[kind].back()));
      }
      out.push_back(std::move(c));
    }
    return out;
  }();
  return all;
}

/// One ray: every reference crossing of an interval reaching deeper than kDepth into the tube
/// must have a solver root within kMatch (distance along the ray); every solver root must lie
/// within kOnSurface of the surface.
void check(const Torus& torus, const Ray& ray, const test::TorusReference& ref, Tally& tally) {
  const double R = torus.majorRadius(), r = torus.minorRadius();
  const double kDepth = 1e-9 * r, kMatch = 1e-5 * r, kOnSurface = 1e-6 * r;
  double t[4];
  const int n = torus.lineRoots(ray, t);
  const double L = length(ray.d);
  ++tally.rays;
  tally.refSteps += ref.steps;
  for (size_t i = 0; i + 1 < ref.roots.size(); i += 2) {
    if (!(ref.depth[i / 2] > kDepth)) continue;
    for (size_t k = i; k <= i + 1; ++k) {
      ++tally.required;
      bool found = false;
      for (int j = 0; j < n; ++j) found |= std::fabs(double(ref.roots[k]) - t[j]) * L < kMatch;
      tally.lost += !found;
      if (!found && std::getenv("TRAY_TORUS_DEBUG") && tally.lost < 4) {
        std::printf("lost: o=(%.9g %.9g %.9g) d=(%.9g %.9g %.9g) ref:", ray.o.x, ray.o.y, ray.o.z,
                    ray.d.x, ray.d.y, ray.d.z);
        for (size_t q = 0; q < ref.roots.size(); ++q) std::printf(" %.12Lg", ref.roots[q]);
        for (size_t q = 0; q < ref.depth.size(); ++q) std::printf(" [depth %.3Lg]", ref.depth[q]);
        std::printf(" solver:");
        for (int j = 0; j < n; ++j) std::printf(" %.12g", t[j]);
        std::printf("\n");
      }
    }
  }
  for (int j = 0; j < n; ++j) {
    const double x = double(ray.o.x) + t[j] * double(ray.d.x),
                 y = double(ray.o.y) + t[j] * double(ray.d.y),
                 z = double(ray.o.z) + t[j] * double(ray.d.z);
    tally.phantom += !(std::fabs(double(torusDistance(R, r, x, y, z))) < kOnSurface);
  }
}

/// Tallies per ray kind for one solver over both tori, printed; returns the totals.
Tally run(QuarticSolver solver, const char* name) {
  Tally total;
  for (const Case& c : cases()) {
    const Torus torus(1.0f, float(c.r), solver);
    for (int k = 0; k < kKinds; ++k) {
      Tally tk;
      for (size_t i = 0; i < c.rays[k].size(); ++i) check(torus, c.rays[k][i], c.refs[k][i], tk);
      std::printf(
          "%-22s r/R=%-5g %-12s %7ld rays, %7ld crossings required: %6ld lost, "
          "%6ld phantom\n",
          name, c.r, kKindNames[k], tk.rays, tk.required, tk.lost, tk.phantom);
      total.rays += tk.rays, total.required += tk.required;
      total.lost += tk.lost, total.phantom += tk.phantom, total.refSteps += tk.refSteps;
    }
  }
  std::printf(
      "%-22s total: %ld rays, %ld crossings required, %ld lost, %ld phantom "
      "(reference: %.0f march steps per ray)\n",
      name, total.rays, total.required, total.lost, total.phantom,
      double(total.refSteps) / double(total.rays));
  return total;
}

// One test, so that the reference (most of the time) is computed once: ctest runs each test
// in a process of its own.
TEST(TorusSolver, TheClosedFormLosesCrossingsPolishingDoesNotHelpIsolationLosesNone) {
  const Tally closed = run(QuarticSolver::kClosedForm, "closed form");
  EXPECT_GT(closed.required, closed.rays);                      // the rays do cross the tori
  EXPECT_GT(closed.lost + closed.phantom, closed.rays / 1000);  // failures are not rare
  const Tally polished = run(QuarticSolver::kClosedFormPolished, "closed form + Newton");
  EXPECT_GT(polished.lost, 0);  // Newton cannot bring back roots the closed form did not return
  const Tally shipped = run(QuarticSolver::kIsolated, "isolated (shipped)");
  EXPECT_EQ(shipped.required, closed.required);
  EXPECT_EQ(shipped.lost, 0);
  EXPECT_EQ(shipped.phantom, 0);
}

}  // namespace
}  // namespace tray
