#pragma once
// Closed triangle meshes built in code for CSG tests: boxes, extruded polygons, a torus; and the
// tessellated twins of the quadrics (quadric_test.cpp, bench/shape_bench.cpp).
#include <algorithm>
#include <cmath>
#include <vector>

#include "core/triangle_mesh.h"
#include "shapes/quadric.h"

namespace tray::test {

/// A prism: the counter-clockwise polygon `poly` (in xy) extruded over z in [z0, z1], wound
/// outward. Side i runs from poly[i] to poly[i + 1]; `sides` picks which sides to emit
/// (empty: all) and `caps` whether to emit the two polygon faces (fan from poly[0]: the
/// polygon must be star-shaped around it).
inline TriangleMesh prismMesh(const std::vector<Vec2>& poly, float z0, float z1, int material,
                              std::vector<bool> sides = {}, bool caps = true) {
  TriangleMesh m;
  m.material = material;
  auto add = [&](Vec3 a, Vec3 b, Vec3 c) {
    uint32_t base = uint32_t(m.positions.size());
    m.positions.insert(m.positions.end(), {a, b, c});
    m.indices.insert(m.indices.end(), {base, base + 1, base + 2});
  };
  size_t n = poly.size();
  for (size_t i = 0; i < n; ++i) {
    if (!sides.empty() && !sides[i]) continue;
    Vec2 a = poly[i], b = poly[(i + 1) % n];
    add({a.x, a.y, z0}, {b.x, b.y, z0}, {b.x, b.y, z1});
    add({a.x, a.y, z0}, {b.x, b.y, z1}, {a.x, a.y, z1});
  }
  if (caps)
    for (size_t i = 1; i + 1 < n; ++i) {
      Vec2 a = poly[0], b = poly[i], c = poly[i + 1];
      add({a.x, a.y, z1}, {b.x, b.y, z1}, {c.x, c.y, z1});
      add({a.x, a.y, z0}, {c.x, c.y, z0}, {b.x, b.y, z0});
    }
  return m;
}

/// The box [lo, hi] as 12 outward triangles.
inline TriangleMesh boxMesh(const Vec3& lo, const Vec3& hi, int material = 0) {
  return prismMesh({{lo.x, lo.y}, {hi.x, lo.y}, {hi.x, hi.y}, {lo.x, hi.y}}, lo.z, hi.z, material);
}

/// A torus around the y axis (ring radius R, tube radius r) with shared vertices.
inline TriangleMesh torusMesh(float R, float r, int nu, int nv, int material = 0) {
  TriangleMesh m;
  m.name = "torus";
  m.material = material;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      float u = 2 * kPi * float(i) / float(nu), v = 2 * kPi * float(j) / float(nv);
      float w = R + r * std::cos(v);
      m.positions.push_back({w * std::cos(u), r * std::sin(v), w * std::sin(u)});
    }
  auto id = [&](int i, int j) { return uint32_t((i % nu) * nv + (j % nv)); };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      uint32_t a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      m.indices.insert(m.indices.end(), {a, c, b, a, d, c});
    }
  return m;
}

/// The quadric's surface of revolution x^2 + z^2 = rho^2(y) as a mesh: nu segments around, nv
/// rows along y (uniform in y; the paraboloid's uniform in rho, its profile being vertical at
/// the apex), plus the caps (fans) when capped. Vertices lie on the analytic surface.
inline TriangleMesh revolvedMesh(const Quadric& q, int nu, int nv) {
  TriangleMesh m;
  m.name = "revolved";
  m.material = 0;
  for (int j = 0; j <= nv; ++j) {
    double w = double(j) / nv;
    double y = q.height() * (q.kind() == Quadric::Kind::kParaboloid ? w * w : w);
    double rho = std::sqrt(std::max(0.0, q.rho2(y)));
    for (int i = 0; i < nu; ++i) {
      double phi = 2 * M_PI * i / nu;
      m.positions.push_back({float(rho * std::sin(phi)), float(y), float(rho * std::cos(phi))});
    }
  }
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      uint32_t a = uint32_t(j * nu + i), b = uint32_t(j * nu + (i + 1) % nu);
      uint32_t c = uint32_t(b + nu), d = uint32_t(a + nu);
      m.indices.insert(m.indices.end(), {a, b, c, a, c, d});
    }
  if (q.capped())
    for (int end = 0; end < 2; ++end) {
      const uint32_t centre = uint32_t(m.positions.size()), base = uint32_t(end * nv * nu);
      m.positions.push_back({0, end ? q.height() : 0.0f, 0});
      for (int i = 0; i < nu; ++i)
        m.indices.insert(m.indices.end(),
                         {centre, base + uint32_t(i), base + uint32_t((i + 1) % nu)});
    }
  return m;
}

}  // namespace tray::test
