#include "shapes/quadric.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace tray {

Quadric::Quadric(Kind kind, float radius, float height, bool capped, float waist)
    : kind_(kind), radius_(radius), height_(height), waist_(waist), capped_(capped) {
  if (!(radius > 0 && height > 0 && std::isfinite(radius) && std::isfinite(height)))
    throw Error("quadric: radius and height must be positive");
  const double r2 = double(radius) * radius, h = height;
  switch (kind) {
    case Kind::kCylinder:
      a_ = 0, b_ = 0, c_ = r2;
      break;
    case Kind::kCone:  // rho = r (1 - y / h)
      a_ = r2 / (h * h), b_ = -2 * r2 / h, c_ = r2;
      break;
    case Kind::kParaboloid:  // rho^2 = r^2 y / h
      a_ = 0, b_ = r2 / h, c_ = 0;
      break;
    case Kind::kHyperboloid: {  // rho^2 = w^2 + k (y - h/2)^2 with rho(0) = rho(h) = r
      if (!(waist >= 0 && waist < radius)) throw Error("hyperboloid: needs 0 <= waist < radius");
      const double w2 = double(waist) * waist, k = 4 * (r2 - w2) / (h * h);
      a_ = k, b_ = -k * h, c_ = w2 + k * h * h / 4;
      break;
    }
  }
}

Bounds3 Quadric::bounds() const {
  return {Vec3(-radius_, 0, -radius_), Vec3(radius_, height_, radius_)};
}

float Quadric::capRadius(int cap) const {
  return float(std::sqrt(std::max(0.0, rho2(cap ? double(height_) : 0.0))));
}

Vec3 Quadric::sideNormal(const Vec3& p) const {
  // Gradient of x^2 + z^2 - rho^2(y), halved.
  return {p.x, float(-(a_ * p.y + 0.5 * b_)), p.z};
}

int Quadric::crossings(const Ray& ray, double t[4], int cap[4]) const {
  const double O0[3] = {ray.o.x, ray.o.y, ray.o.z}, D[3] = {ray.d.x, ray.d.y, ray.d.z};
  const double L = std::sqrt(D[0] * D[0] + D[1] * D[1] + D[2] * D[2]);
  if (!(L > 0) || !std::isfinite(L)) return 0;
  const double u[3] = {D[0] / L, D[1] / L, D[2] / L};
  // As for the torus: solve about the line's point nearest the shape's middle, in double.
  const double mid = 0.5 * height_;
  const double s0 = -(O0[0] * u[0] + (O0[1] - mid) * u[1] + O0[2] * u[2]);
  const double O[3] = {O0[0] + s0 * u[0], O0[1] + s0 * u[1], O0[2] + s0 * u[2]};
  // q(s) = x^2 + z^2 - rho^2(y) along the line: <= 0 inside the infinite quadric.
  const double A = u[0] * u[0] + u[2] * u[2] - a_ * u[1] * u[1];
  const double B = 2 * (O[0] * u[0] + O[2] * u[2] - a_ * O[1] * u[1]) - b_ * u[1];
  const double C = O[0] * O[0] + O[2] * O[2] - rho2(O[1]);
  // Roots of q, ascending (stable form).
  double root[2];
  int nr = 0;
  if (A != 0) {
    const double disc = B * B - 4 * A * C;
    if (disc > 0) {
      const double q = -0.5 * (B + std::copysign(std::sqrt(disc), B));
      root[0] = q / A, root[1] = q != 0 ? C / q : -root[0];
      if (root[0] > root[1]) std::swap(root[0], root[1]);
      nr = 2;
    }
  } else if (B != 0) {
    root[0] = -C / B, nr = 1;
  }
  // The slab 0 <= y <= height.
  double lo = -INFINITY, hi = INFINITY;
  if (u[1] != 0) {
    lo = (0 - O[1]) / u[1], hi = (height_ - O[1]) / u[1];
    if (lo > hi) std::swap(lo, hi);
  } else if (!(O[1] >= 0 && O[1] <= height_)) {
    return 0;
  }
  const auto yCap = [&](double s) { return O[1] + s * u[1] > mid ? 1 : 0; };
  int n = 0;
  if (!capped_) {
    for (int i = 0; i < nr; ++i)
      if (root[i] >= lo && root[i] <= hi) t[n] = root[i], cap[n++] = -1;
  } else {
    // Stretches where q <= 0, then clipped by the slab.
    double span[4];
    int ns = 0;
    const double qFar = A != 0 ? A : B;  // sign of q towards +infinity (A = B = 0: constant)
    if (nr == 2 && A > 0) {
      span[ns++] = root[0], span[ns++] = root[1];
    } else if (nr == 2) {
      span[ns++] = -INFINITY, span[ns++] = root[0], span[ns++] = root[1], span[ns++] = INFINITY;
    } else if (nr == 1) {
      if (qFar > 0)
        span[ns++] = -INFINITY, span[ns++] = root[0];
      else
        span[ns++] = root[0], span[ns++] = INFINITY;
    } else if (A < 0 || (A == 0 && B == 0 && C <= 0)) {
      span[ns++] = -INFINITY, span[ns++] = INFINITY;
    }
    for (int i = 0; i + 1 < ns; i += 2) {
      const double a = std::max(span[i], lo), b = std::min(span[i + 1], hi);
      if (!(a < b)) continue;
      t[n] = a, cap[n++] = a == lo ? yCap(a) : -1;
      t[n] = b, cap[n++] = b == hi ? yCap(b) : -1;
    }
  }
  for (int i = 0; i < n; ++i) t[i] = (s0 + t[i]) / L;
  return n;
}

Vec2 Quadric::uvAt(const Vec3& p, int cap) const {
  float phi = std::atan2(p.x, p.z);
  if (phi < 0) phi += 2.0f * kPi;
  if (cap < 0) return {phi / (2.0f * kPi), std::clamp(p.y / height_, 0.0f, 1.0f)};
  const float rc = capRadius(cap);
  return {phi / (2.0f * kPi), rc > 0 ? std::sqrt(p.x * p.x + p.z * p.z) / rc : 0.0f};
}

Crossing Quadric::crossingAt(const Ray& ray, double t, int cap) const {
  Crossing c;
  c.t = float(t);
  // In double: a ray from far away keeps the digits of the point it hits.
  Vec3 p(float(double(ray.o.x) + t * double(ray.d.x)), float(double(ray.o.y) + t * double(ray.d.y)),
         float(double(ray.o.z) + t * double(ray.d.z)));
  if (cap >= 0) {
    p.y = cap ? height_ : 0.0f;
    c.normal = Vec3(0, cap ? 1.0f : -1.0f, 0);
  } else {
    c.normal = sideNormal(p);
  }
  c.uv = uvAt(p, cap);
  return c;
}

bool Quadric::intersect(const Ray& ray, Hit& hit) const {
  double t[4];
  int cap[4];
  const int n = crossings(ray, t, cap);
  for (int i = 0; i < n; ++i) {
    const float tf = float(t[i]);
    if (!(tf > ray.tmin) || !std::isfinite(tf)) continue;
    if (!(tf < ray.tmax)) return false;
    const Crossing c = crossingAt(ray, t[i], cap[i]);
    hit.t = c.t;
    hit.normal = c.normal;
    hit.uv = c.uv;
    return true;
  }
  return false;
}

void Quadric::intervals(const Ray& ray, std::vector<Interval>& out) const {
  if (!capped_) return;  // not a solid
  double t[4];
  int cap[4];
  const int n = crossings(ray, t, cap);
  for (int i = 0; i + 1 < n; i += 2)
    out.push_back({crossingAt(ray, t[i], cap[i]), crossingAt(ray, t[i + 1], cap[i + 1])});
}

void Quadric::uvDerivatives(const Vec3& p, const Vec3& n, Vec3& dpdu, Vec3& dpdv) const {
  dpdu = 2.0f * kPi * Vec3(p.z, 0.0f, -p.x);
  const float rho = std::sqrt(p.x * p.x + p.z * p.z);
  const bool onCap = capped_ && std::fabs(n.x) + std::fabs(n.z) < 1e-6f * std::fabs(n.y);
  if (onCap) {
    const float rc = capRadius(p.y > 0.5f * height_ ? 1 : 0);
    dpdv = rho > 0 ? (rc / rho) * Vec3(p.x, 0.0f, p.z) : Vec3(0.0f);
    return;
  }
  // d(x, z)/dy = (x, z) rho'/rho with rho rho' = (2 a y + b) / 2.
  const float k = rho > 0 ? float((a_ * p.y + 0.5 * b_) / (rho * rho)) : 0.0f;
  dpdv = height_ * Vec3(k * p.x, 1.0f, k * p.z);
}

Vec3 Quadric::refine(const Vec3& p) const {
  // Onto the nearest cap plane or radially onto the side, whichever is nearer (the radial
  // projection is exact for the cylinder and within float rounding of the hit for the rest).
  const double rho = std::sqrt(double(p.x) * p.x + double(p.z) * p.z);
  const double want = std::sqrt(std::max(0.0, rho2(std::clamp(double(p.y), 0.0, double(height_)))));
  const double dSide = std::fabs(rho - want);
  if (capped_) {
    const double d0 = std::fabs(p.y), d1 = std::fabs(p.y - height_);
    if (std::min(d0, d1) < dSide) return {p.x, d0 < d1 ? 0.0f : height_, p.z};
  }
  if (!(rho > 0)) return p;
  const double k = want / rho;
  return {float(p.x * k), p.y, float(p.z * k)};
}

}  // namespace tray
