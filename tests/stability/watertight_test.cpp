// Stability 2: grazing and tangent rays find no holes. Rays aimed exactly at the shared edges
// and vertices of a closed mesh, at steep and grazing angles, must all hit it (watertight ray/
// triangle tests, Woop, Benthin & Wald 2013); rays passing just inside an analytic sphere's
// silhouette must hit it and rays just outside must miss. Checked for every registered
// accelerator.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "accel/registry.h"
#include "tests/stability/stability_scenes.h"

namespace tray {
namespace {

using namespace tray::stability;

/// Double-precision vectors: the test's rays are constructed exactly, then rounded once.
struct D3 {
  double x, y, z;
  D3 operator+(const D3& o) const { return {x + o.x, y + o.y, z + o.z}; }
  D3 operator-(const D3& o) const { return {x - o.x, y - o.y, z - o.z}; }
  D3 operator*(double s) const { return {x * s, y * s, z * s}; }
};
double dot(const D3& a, const D3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
D3 cross(const D3& a, const D3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
D3 unit(const D3& a) {
  return a * (1.0 / std::sqrt(dot(a, a)));
}
D3 toD3(const Vec3& v) {
  return {v.x, v.y, v.z};
}
Vec3 toVec3(const D3& v) {
  return {float(v.x), float(v.y), float(v.z)};
}

/// A ray that crosses the surface at `target` into the solid. `depth` is how far past the
/// target along the ray the line is still strictly inside the solid: a first hit later than
/// that means the ray went through a crack.
struct AimedRay {
  Ray ray;
  double targetT, depth;
  std::vector<uint32_t> triangles;  ///< the triangles around the target (edge: 2, vertex: fan)
  bool atVertex = false;            ///< aimed exactly at a vertex (else at an edge)
};

constexpr double kDeg = 3.14159265358979323846 / 180.0;
const double kGrazingAngles[] = {30 * kDeg, 1 * kDeg, 0.05 * kDeg};

/// Builds a ray entering through `target` along unit `d`; its origin is 3 units back.
AimedRay aim(const D3& target, const D3& d, double depth, std::vector<uint32_t> triangles) {
  const double back = 3.0;
  const D3 o = target - d * back;
  return {Ray{toVec3(o), toVec3(d), 0.0f, kInfinity}, back, depth, std::move(triangles)};
}

/// Every ray of the test: at points 1/2 and 3/10 along each edge, and at each vertex; towards
/// the centre, and at each grazing angle along the edge (both ways) and across it (into each
/// face).
std::vector<AimedRay> aimedRays(const TriangleMesh& m) {
  std::map<std::pair<uint32_t, uint32_t>, std::vector<uint32_t>> edges;
  std::vector<std::vector<uint32_t>> fans(m.positions.size());
  std::vector<D3> faceNormal(m.triangleCount());
  for (uint32_t t = 0; t < m.triangleCount(); ++t) {
    const uint32_t* v = &m.indices[3 * t];
    const D3 a = toD3(m.positions[v[0]]), b = toD3(m.positions[v[1]]), c = toD3(m.positions[v[2]]);
    faceNormal[t] = unit(cross(b - a, c - a));
    for (int k = 0; k < 3; ++k) {
      edges[std::minmax(v[k], v[(k + 1) % 3])].push_back(t);
      fans[v[k]].push_back(t);
    }
  }
  auto third = [&](uint32_t t, uint32_t a, uint32_t b) {
    for (int k = 0; k < 3; ++k)
      if (m.indices[3 * t + k] != a && m.indices[3 * t + k] != b) return m.indices[3 * t + k];
    return a;
  };
  std::vector<AimedRay> rays;
  for (const auto& [edge, faces] : edges) {
    const D3 a = toD3(m.positions[edge.first]), b = toD3(m.positions[edge.second]);
    const double len = std::sqrt(dot(b - a, b - a));
    const D3 along = unit(b - a), n = unit(faceNormal[faces[0]] + faceNormal[faces[1]]);
    for (double s : {0.5, 0.3}) {
      const D3 e = a + (b - a) * s;
      const double room = 0.5 * s * len;  // stays on the edge / in the face for this long
      rays.push_back(aim(e, unit(e * -1.0), 0.5, faces));
      for (double angle : kGrazingAngles) {
        const double c = std::cos(angle), sn = std::sin(angle);
        for (double sign : {1.0, -1.0})
          rays.push_back(aim(e, unit(along * (sign * c) - n * sn), room, faces));
        for (uint32_t f : faces) {  // across the edge, into face f, just under its plane
          const D3 into = unit(toD3(m.positions[third(f, edge.first, edge.second)]) - e);
          D3 across = unit(cross(faceNormal[f], along));
          if (dot(across, into) < 0) across = across * -1.0;
          rays.push_back(aim(e, unit(across * c - faceNormal[f] * sn), room, faces));
        }
      }
    }
  }
  const size_t edgeRays = rays.size();
  for (uint32_t v = 0; v < m.positions.size(); ++v) {
    const D3 p = toD3(m.positions[v]), n = unit(p);
    rays.push_back(aim(p, n * -1.0, 0.5, fans[v]));
    for (uint32_t t : fans[v])  // grazing along one edge of each incident triangle
      for (double angle : kGrazingAngles) {
        const uint32_t w = m.indices[3 * t] == v       ? m.indices[3 * t + 1]
                           : m.indices[3 * t + 1] == v ? m.indices[3 * t + 2]
                                                       : m.indices[3 * t];
        const D3 toW = toD3(m.positions[w]) - p;
        const double room = 0.25 * std::sqrt(dot(toW, toW));
        rays.push_back(
            aim(p, unit(unit(toW) * std::cos(angle) - n * std::sin(angle)), room, fans[v]));
      }
  }
  for (size_t i = edgeRays; i < rays.size(); ++i) rays[i].atVertex = true;
  return rays;
}

bool isHole(const AimedRay& r, bool hit, float t) {
  return !hit || double(t) > r.targetT + r.depth;
}

TEST(Watertight, RaysAtSharedEdgesAndVerticesNeverFallThrough) {
  Scene s;
  const int mat = addMaterial(s, diffuse(Color(0.5f)));
  const TriangleMesh sphere = geodesicSphere(4, mat);
  addMeshInstance(s, addMesh(s, sphere), Mat4::identity());
  s.finalize();
  const std::vector<AimedRay> rays = aimedRays(sphere);
  ASSERT_GT(rays.size(), 100000u);
  const size_t vertexRays =
      size_t(std::count_if(rays.begin(), rays.end(), [](const AimedRay& r) { return r.atVertex; }));
  for (const std::string& name : acceleratorNames()) {
    if (name == "naive") continue;  // the same triangle test as bvh, without the 30 s
    auto accel = makeAccelerator(name, s);
    size_t edgeHoles = 0, vertexHoles = 0, occlusionMismatches = 0;
    for (const AimedRay& r : rays) {
      Hit hit;
      const bool found = accel->intersect(r.ray, hit);
      if (isHole(r, found, hit.t)) ++(r.atVertex ? vertexHoles : edgeHoles);
      occlusionMismatches += found != accel->occluded(r.ray);
    }
    std::printf(
        "%s: %zu rays at the %zu edges and %zu vertices of a %zu-triangle sphere: %zu "
        "holes at edges, %zu at vertices (of %zu vertex rays)\n",
        name.c_str(), rays.size(), sphere.triangleCount() * 3 / 2, sphere.positions.size(),
        sphere.triangleCount(), edgeHoles, vertexHoles, vertexRays);
    EXPECT_EQ(edgeHoles, 0u) << name;
    EXPECT_EQ(occlusionMismatches, 0u) << name;
    if (name == "embree") {
      // Embree 3's robust mode is watertight along edges but leaves "very tiny cracks at the
      // vertices" (its authors, RenderKit/embree#174, #181, #188): a ray aimed exactly at a
      // vertex can pass between the fan's triangles. Measured: 528 of 104k vertex rays. TRay's
      // own BVH (Woop et al. 2013 with a double-precision fallback) is the watertight reference.
      EXPECT_LT(vertexHoles, vertexRays / 50)
          << name << ": more vertex cracks than Embree 3.13 has";
    } else {
      EXPECT_EQ(vertexHoles, 0u) << name;
    }
  }
}

/// Möller & Trumbore (1997) in float with the usual inclusive bounds: the textbook test that is
/// not watertight, for contrast. Each triangle computes its barycentrics with its own rounding,
/// so along a shared edge both neighbours can reject the same ray.
bool mollerTrumbore(const Ray& ray, const Vec3& a, const Vec3& b, const Vec3& c, float& t) {
  const Vec3 e1 = b - a, e2 = c - a, p = tray::cross(ray.d, e2);
  const float det = tray::dot(e1, p);
  if (det == 0) return false;
  const float inv = 1.0f / det;
  const Vec3 s = ray.o - a;
  const float u = tray::dot(s, p) * inv;
  if (u < 0 || u > 1) return false;
  const Vec3 q = tray::cross(s, e1);
  const float v = tray::dot(ray.d, q) * inv;
  if (v < 0 || u + v > 1) return false;
  t = tray::dot(e2, q) * inv;
  return t > 0;
}

TEST(Watertight, TheTextbookTriangleTestLeaksOnSharedEdges) {
  const TriangleMesh sphere = geodesicSphere(4, 0);
  size_t holes = 0;
  const std::vector<AimedRay> rays = aimedRays(sphere);
  for (const AimedRay& r : rays) {
    bool found = false;
    float best = kInfinity;
    for (uint32_t tri : r.triangles) {
      const uint32_t* v = &sphere.indices[3 * tri];
      float t;
      if (mollerTrumbore(r.ray, sphere.positions[v[0]], sphere.positions[v[1]],
                         sphere.positions[v[2]], t) &&
          t < best)
        found = true, best = t;
    }
    holes += isHole(r, found, best);
  }
  std::printf("textbook Moller-Trumbore: %zu holes in %zu rays (%.3f%%)\n", holes, rays.size(),
              100.0 * double(holes) / double(rays.size()));
  EXPECT_GT(holes, 0u);  // the demonstration above would catch a non-watertight test
}

// --- Tangent rays at an analytic sphere ------------------------------------------------------

constexpr double kRadius = 2.0, kDistance = 1000.0;  // origins 500 radii away
const D3 kCentre{3, -2, 5};

/// Rays from kDistance away passing the sphere's centre at impact parameter radius x (1 + eps),
/// over many directions: inside the silhouette for eps < 0, outside for eps > 0.
std::vector<Ray> tangentRays(double eps) {
  std::vector<Ray> rays;
  for (int i = 0; i < 400; ++i) {
    // Fibonacci-sphere directions, an offset direction perpendicular to each.
    const double z = 1 - 2 * (i + 0.5) / 400, r = std::sqrt(1 - z * z), phi = i * 2.39996322972865;
    const D3 d{r * std::cos(phi), r * std::sin(phi), z};
    const D3 helper = std::fabs(d.z) < 0.9 ? D3{0, 0, 1} : D3{1, 0, 0};
    const D3 u = unit(cross(d, helper)), w = cross(d, u);
    const double psi = i * 0.7;
    const D3 side = u * std::cos(psi) + w * std::sin(psi);
    const D3 o = kCentre + side * (kRadius * (1 + eps)) - d * kDistance;
    rays.push_back(Ray{toVec3(o), toVec3(d), 0.0f, kInfinity});
  }
  return rays;
}

const double kEps[] = {-1e-2, -3e-3, -1e-3, 1e-3, 3e-3, 1e-2};

TEST(Watertight, TangentRaysAtASphereHitInsideAndMissOutsideTheSilhouette) {
  Scene s;
  addShape(s, std::make_shared<Sphere>(float(kRadius)), Mat4::translate(toVec3(kCentre)),
           addMaterial(s, diffuse(Color(0.5f))));
  s.finalize();
  for (const std::string& name : acceleratorNames()) {
    auto accel = makeAccelerator(name, s);
    size_t wrong = 0, total = 0;
    for (double eps : kEps)
      for (const Ray& ray : tangentRays(eps)) {
        Hit hit;
        const bool found = accel->intersect(ray, hit);
        ++total;
        if (found != (eps < 0)) {
          ++wrong;
          continue;
        }
        if (found) {  // the hit lies on the sphere, near the silhouette
          const D3 p = toD3(ray.o + hit.t * ray.d) - kCentre;
          EXPECT_NEAR(std::sqrt(dot(p, p)), kRadius, 1e-3) << name;
        }
      }
    std::printf(
        "%s: %zu tangent rays (impact parameter radius x (1 +- 1e-3 .. 1e-2), from %g "
        "radii): %zu wrong\n",
        name.c_str(), total, kDistance / kRadius, wrong);
    EXPECT_EQ(wrong, 0u) << name;
  }
}

TEST(Watertight, TheTextbookSphereDiscriminantFailsNearTheSilhouette) {
  // b^2 - c with b = o.d and c = |o|^2 - r^2 in float: at 500 radii |o|^2 carries an absolute
  // rounding error of about 0.06 r^2, larger than the discriminant near the silhouette.
  size_t wrong = 0, total = 0;
  const Vec3 centre = toVec3(kCentre);
  for (double eps : kEps)
    for (const Ray& ray : tangentRays(eps)) {
      const Vec3 o = ray.o - centre;
      const float b = tray::dot(o, ray.d), c = tray::dot(o, o) - float(kRadius * kRadius);
      const bool found = b * b - c >= 0;
      wrong += found != (eps < 0);
      ++total;
    }
  std::printf("textbook discriminant: %zu of %zu tangent rays wrong\n", wrong, total);
  EXPECT_GT(wrong, total / 10);
}

}  // namespace
}  // namespace tray
