#include "shapes/torus.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "shapes/polynomial_roots.h"

namespace tray {

Torus::Torus(float majorRadius, float minorRadius, QuarticSolver solver)
    : R_(majorRadius), r_(minorRadius), solver_(solver) {
  if (!(minorRadius > 0 && majorRadius > minorRadius && std::isfinite(majorRadius)))
    throw Error("torus: needs major radius > minor radius > 0");
}

Bounds3 Torus::bounds() const {
  const float w = R_ + r_;
  return {Vec3(-w, -r_, -w), Vec3(w, r_, w)};
}

void Torus::quartic(const double o[3], const double u[3], double c[5]) const {
  // p = o + s u in (|p|^2 + R^2 - r^2)^2 - 4 R^2 (x^2 + z^2); negative inside.
  const double R = R_, r = r_, R2 = R * R;
  const double m = o[0] * o[0] + o[1] * o[1] + o[2] * o[2];
  const double b = o[0] * u[0] + o[1] * u[1] + o[2] * u[2];
  const double K = m + R2 - r * r;
  const double rho = std::sqrt(o[0] * o[0] + o[2] * o[2]);
  c[4] = 1.0;
  c[3] = 4.0 * b;
  c[2] = 4.0 * b * b + 2.0 * K - 4.0 * R2 * (u[0] * u[0] + u[2] * u[2]);
  c[1] = 4.0 * b * K - 8.0 * R2 * (o[0] * u[0] + o[2] * u[2]);
  // K^2 - 4 R^2 rho^2 factored: K - 2 R rho = (rho - R)^2 + y^2 - r^2 is the tube's own
  // implicit function, free of the cancellation of the difference of squares near the surface.
  c[0] = ((rho - R) * (rho - R) + o[1] * o[1] - r * r) * (K + 2.0 * R * rho);
}

namespace {

/// Newton steps on the quartic from a closed-form root (the "polished" variant).
double polish(const double c[5], double s) {
  for (int i = 0; i < 4; ++i) {
    double p = c[4], dp = 0.0;
    for (int k = 3; k >= 0; --k) dp = dp * s + p, p = p * s + c[k];
    if (dp == 0.0) break;
    s -= p / dp;
  }
  return s;
}

}  // namespace

int Torus::lineRoots(const Ray& ray, double t[4]) const {
  const double O[3] = {ray.o.x, ray.o.y, ray.o.z}, D[3] = {ray.d.x, ray.d.y, ray.d.z};
  const double L = std::sqrt(D[0] * D[0] + D[1] * D[1] + D[2] * D[2]);
  if (!(L > 0) || !std::isfinite(L)) return 0;
  const double u[3] = {D[0] / L, D[1] / L, D[2] / L};
  // Move the origin to the line's point nearest the centre and solve for s = t L - s0: the
  // coefficients are then of the torus' size however far the ray starts (a ray from 1e4 away
  // would otherwise need 16 digits just to cancel its own distance).
  const double s0 = -(O[0] * u[0] + O[1] * u[1] + O[2] * u[2]);
  const double P[3] = {O[0] + s0 * u[0], O[1] + s0 * u[1], O[2] + s0 * u[2]};
  const double outer = double(R_) + double(r_), r = r_;
  const double m = P[0] * P[0] + P[1] * P[1] + P[2] * P[2];
  if (!(m < outer * outer)) return 0;  // misses the bounding sphere (or NaN)
  const double h = std::sqrt(outer * outer - m);
  double lo = -h, hi = h;
  // ... and the slab |y| <= r holding the tube.
  if (u[1] != 0.0) {
    double a = (-r - P[1]) / u[1], b = (r - P[1]) / u[1];
    if (a > b) std::swap(a, b);
    lo = std::max(lo, a), hi = std::min(hi, b);
  } else if (!(std::fabs(P[1]) < r)) {
    return 0;
  }
  if (!(lo < hi)) return 0;
  // Ends strictly outside, so every crossing is a sign change inside [lo, hi].
  const double pad = 1e-9 * outer;
  lo -= pad, hi += pad;
  double c[5], s[4];
  quartic(P, u, c);
  int n = 0;
  if (solver_ == QuarticSolver::kIsolated) {
    n = polyRootsIsolated(c, 4, lo, hi, s);
  } else {
    n = solveQuarticClosedForm(c, s);
    if (solver_ == QuarticSolver::kClosedFormPolished)
      for (int i = 0; i < n; ++i) s[i] = polish(c, s[i]);
    for (int i = 1; i < n; ++i)  // insertion sort of at most 4
      for (int k = i; k > 0 && s[k] < s[k - 1]; --k) std::swap(s[k], s[k - 1]);
  }
  for (int i = 0; i < n; ++i) t[i] = (s0 + s[i]) / L;
  return n;
}

Vec3 Torus::normalAt(const Vec3& p) const {
  const float rho = std::sqrt(p.x * p.x + p.z * p.z);
  if (!(rho > 0)) return Vec3(0, 1, 0);
  const float k = R_ / rho;
  return {p.x - k * p.x, p.y, p.z - k * p.z};
}

Vec2 Torus::uvAt(const Vec3& p) const {
  float phi = std::atan2(p.x, p.z);
  if (phi < 0) phi += 2.0f * kPi;
  float theta = std::atan2(p.y, std::sqrt(p.x * p.x + p.z * p.z) - R_);
  if (theta < 0) theta += 2.0f * kPi;
  return {phi / (2.0f * kPi), theta / (2.0f * kPi)};
}

void Torus::uvDerivatives(const Vec3& p, const Vec3&, Vec3& dpdu, Vec3& dpdv) const {
  // p = ((R + r cos theta) sin phi, r sin theta, (R + r cos theta) cos phi), phi = 2 pi u,
  // theta = 2 pi v.
  const float phi = std::atan2(p.x, p.z);
  const float theta = std::atan2(p.y, std::sqrt(p.x * p.x + p.z * p.z) - R_);
  dpdu = 2.0f * kPi * Vec3(p.z, 0.0f, -p.x);
  const float st = std::sin(theta), ct = std::cos(theta);
  dpdv = 2.0f * kPi * r_ * Vec3(-st * std::sin(phi), ct, -st * std::cos(phi));
}

namespace {

/// o + t d in double: a ray from far away keeps the digits of the point it hits, which a thin
/// tube's normal needs (float o + t d is off by |o| 6e-8).
Vec3 pointAt(const Ray& ray, double t) {
  return {float(double(ray.o.x) + t * double(ray.d.x)),
          float(double(ray.o.y) + t * double(ray.d.y)),
          float(double(ray.o.z) + t * double(ray.d.z))};
}

}  // namespace

bool Torus::intersect(const Ray& ray, Hit& hit) const {
  double t[4];
  const int n = lineRoots(ray, t);
  for (int i = 0; i < n; ++i) {
    const float tf = float(t[i]);
    if (!(tf > ray.tmin)) continue;
    if (!(tf < ray.tmax)) return false;
    const Vec3 p = pointAt(ray, t[i]);
    hit.t = tf;
    hit.normal = normalAt(p);
    hit.uv = uvAt(p);
    return true;
  }
  return false;
}

void Torus::intervals(const Ray& ray, std::vector<Interval>& out) const {
  double t[4];
  const int n = lineRoots(ray, t);
  // Roots alternate entering / leaving (the line starts and ends outside); an odd count (the
  // closed forms lose roots) drops the unpaired last one.
  for (int i = 0; i + 1 < n; i += 2) {
    Interval iv;
    Crossing* ends[2] = {&iv.enter, &iv.exit};
    for (int k = 0; k < 2; ++k) {
      const Vec3 p = pointAt(ray, t[i + k]);
      ends[k]->t = float(t[i + k]);
      ends[k]->normal = normalAt(p);
      ends[k]->uv = uvAt(p);
    }
    out.push_back(iv);
  }
}

Vec3 Torus::refine(const Vec3& p) const {
  const double x = p.x, y = p.y, z = p.z, rho = std::sqrt(x * x + z * z);
  if (!(rho > 0)) return p;
  const double cx = R_ * x / rho, cz = R_ * z / rho;  // nearest point of the centre circle
  const double dx = x - cx, dz = z - cz, len = std::sqrt(dx * dx + y * y + dz * dz);
  if (!(len > 0)) return p;
  const double k = r_ / len;
  return {float(cx + k * dx), float(k * y), float(cz + k * dz)};
}

}  // namespace tray
