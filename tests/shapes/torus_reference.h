#pragma once
// An independent reference for ray-torus crossings (tests only): the torus' exact distance
// function g(p) = |(sqrt(x^2 + z^2) - R, y)| - r, marched along the line in long double and
// bisected at every sign change. g is 1-Lipschitz, so a step of |g| never crosses the surface
// (sphere tracing, Hart 1996); near the surface the step is at least kMinStep = 1e-5 r, so
// only a chord shorter than that can be stepped over: with normal curvatures at most 1/r, a
// penetration depth below kMinStep^2 / 8r = 1.25e-11 r (callers require crossings only of
// intervals deeper than that). No polynomial, no closed form: nothing shared with
// shapes/torus.cpp.
#include <cmath>
#include <vector>

#include "core/ray.h"

namespace tray::test {

struct TorusReference {
  /// Crossings of the line, ascending, in the ray's t; depth[i] of the interval
  /// [roots[2i], roots[2i+1]]: how far inside the tube it reaches (the largest -g sampled).
  std::vector<long double> roots, depth;
  long steps = 0;
};

inline long double torusDistance(long double R, long double r, long double x, long double y,
                                 long double z) {
  const long double a = std::sqrt(x * x + z * z) - R;
  return std::sqrt(a * a + y * y) - r;
}

inline TorusReference torusReference(double R, double r, const Ray& ray) {
  TorusReference out;
  const long double ox = ray.o.x, oy = ray.o.y, oz = ray.o.z;
  const long double dx = ray.d.x, dy = ray.d.y, dz = ray.d.z;
  const long double L = std::sqrt(dx * dx + dy * dy + dz * dz);
  const long double RR = R, rr = r, outer = RR + rr;
  // The chord of the bounding sphere |p| <= R + r (slightly enlarged).
  const long double b = (ox * dx + oy * dy + oz * dz) / L;
  const long double m = ox * ox + oy * oy + oz * oz;
  const long double disc = b * b - (m - outer * outer * 1.0001L);
  if (!(disc > 0)) return out;
  const long double tA = (-b - std::sqrt(disc)) / L, tB = (-b + std::sqrt(disc)) / L;
  const long double kMinStep = 1e-5L * rr / L;
  auto g = [&](long double t) {
    return torusDistance(RR, rr, ox + t * dx, oy + t * dy, oz + t * dz);
  };
  long double t = tA, gt = g(t), deepest = 0;
  while (t < tB) {
    ++out.steps;
    const long double tn = std::min(tB, t + std::max(std::fabs(gt) / L, kMinStep));
    const long double gn = g(tn);
    if ((gn < 0) != (gt < 0)) {
      long double a = t, c = tn;
      const bool insideA = gt < 0;
      for (int i = 0; i < 100 && c - a > 0; ++i) {
        const long double mid = 0.5L * (a + c);
        if (mid <= a || mid >= c) break;
        if ((g(mid) < 0) == insideA)
          a = mid;
        else
          c = mid;
      }
      out.roots.push_back(0.5L * (a + c));
      if (!insideA)
        deepest = 0;
      else
        out.depth.push_back(deepest);
    }
    if (gn < 0) deepest = std::max(deepest, -gn);
    t = tn, gt = gn;
  }
  return out;
}

}  // namespace tray::test
