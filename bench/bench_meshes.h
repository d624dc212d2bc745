#pragma once
// Procedural meshes for bench/accel_bench.cpp: a tessellated (bumpy) sphere of any size, and a
// teapot-shaped object (a lathed body and lid, a tube spout and a torus handle). The teapot is
// drawn from simple profile curves written here, not from Newell's patch data; it has the same
// parts and a similar triangle distribution (dense knob and spout, large smooth body).
#include <cmath>
#include <functional>

#include "core/triangle_mesh.h"

namespace tray::bench {

/// Appends a (u, v) grid surface: `pos(u, v)` for u, v in [0, 1], nu x nv quads, two triangles
/// each; u wraps when `wrapU`.
inline void addGrid(TriangleMesh& m, int nu, int nv, bool wrapU,
                    const std::function<Vec3(float, float)>& pos) {
  const uint32_t base = uint32_t(m.positions.size());
  const int cols = wrapU ? nu : nu + 1;
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i < cols; ++i) m.positions.push_back(pos(float(i) / nu, float(j) / nv));
  auto at = [&](int i, int j) { return base + uint32_t(j * cols + (i % cols)); };
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      uint32_t a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      m.indices.insert(m.indices.end(), {a, b, c, a, c, d});
    }
}

/// A unit sphere with small bumps, about `triangles` triangles (2 n^2 for an n x n grid).
inline TriangleMesh bumpySphere(size_t triangles) {
  TriangleMesh m;
  int n = std::max(4, int(std::sqrt(double(triangles) / 2.0)));
  addGrid(m, n, n, true, [](float u, float v) {
    float phi = 2 * kPi * u, theta = kPi * v;
    float r = 1.0f + 0.03f * std::sin(23 * phi) * std::sin(17 * theta);
    return Vec3(r * std::sin(theta) * std::cos(phi), r * std::cos(theta),
                r * std::sin(theta) * std::sin(phi));
  });
  return m;
}

/// A teapot-shaped mesh about 3 units wide; `res` sets the tessellation (res 32: ~17k triangles).
inline TriangleMesh teapot(int res) {
  TriangleMesh m;
  auto lathe = [&](int nu, int nv, auto radius, float y0, float y1) {
    addGrid(m, nu, nv, true, [=](float u, float v) {
      float y = y0 + (y1 - y0) * v, r = radius(v), phi = 2 * kPi * u;
      return Vec3(r * std::cos(phi), y, r * std::sin(phi));
    });
  };
  // Body: a squashed bulb, widest a third of the way up.
  lathe(4 * res, 2 * res, [](float v) { return 0.05f + 1.35f * std::pow(std::sin(kPi * (0.08f + 0.86f * v)), 0.7f) * (1.0f - 0.25f * v); }, 0.0f, 1.5f);
  // Lid and knob.
  lathe(3 * res, res, [](float v) { return 0.95f * (1.0f - v) + 0.12f; }, 1.45f, 1.75f);
  lathe(2 * res, res, [](float v) { return 0.2f * std::sin(kPi * std::min(v, 0.999f)) + 0.02f; }, 1.75f, 2.0f);
  // Spout: a tube along a rising curve, thinning towards the tip.
  addGrid(m, res, 2 * res, true, [](float u, float v) {
    Vec3 c{1.1f + 0.9f * v, 0.5f + 0.9f * v * v, 0.0f};
    Vec3 tangent = normalize(Vec3(0.9f, 1.8f * v, 0.0f)), side{0, 0, 1};
    Vec3 up = cross(side, tangent);
    float r = 0.25f - 0.13f * v, phi = 2 * kPi * u;
    return c + r * (std::cos(phi) * up + std::sin(phi) * side);
  });
  // Handle: part of a torus on the other side.
  addGrid(m, res, 2 * res, true, [](float u, float v) {
    float a = -0.45f * kPi + 0.9f * kPi * v, phi = 2 * kPi * u;
    Vec3 c{-1.15f - 0.45f * std::cos(a), 0.85f + 0.45f * std::sin(a), 0.0f};
    Vec3 radial = normalize(Vec3(-std::cos(a), std::sin(a), 0.0f));
    return c + 0.08f * (std::cos(phi) * radial + std::sin(phi) * Vec3(0, 0, 1));
  });
  return m;
}

}  // namespace tray::bench
