// Instance arrays in both accelerators (docs/instancing.md, "Instance arrays"): the top trees
// over groups of instances with their instances' own boxes (accel/bvh_instance_boxes.h, the
// in-house BVH's leaves and Embree's user primitives, accel/embree_instance_array.h) give the
// closest hit, instance and t, that brute force over every instance finds, and the same
// occlusion, on random rays, one by one and in batches. 2003 instances: groups of 8 and a last
// partial one.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "accel/registry.h"
#include "core/accelerator.h"
#include "core/instance_array.h"
#include "tests/scene_builder.h"

namespace tray {
namespace {

using namespace tray::test;

constexpr uint32_t kInstances = 2003;

/// A perturbed octahedron (8 triangles) around the origin, the mesh every instance places.
TriangleMesh octahedron(int material) {
  TriangleMesh m;
  m.positions = {{1.0f, 0.1f, 0},  {-0.9f, 0, 0.1f}, {0, 1.1f, 0},
                 {0.1f, -1.0f, 0}, {0, 0, 0.8f},     {0, 0.1f, -1.2f}};
  m.indices = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
  m.material = material;
  return m;
}

struct World {
  Scene scene;
  std::vector<Mat4> toWorld;  ///< per instance
};

/// The instances placed at random (rotation, non-uniform scale and shear) in a 40-unit cube,
/// about 0.3 to 1.5 units across, many overlapping; one instance array, as the glTF loader
/// makes (gltf/gltf_scene_graph.cpp, placeArray).
World randomArray() {
  World w;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<float> u(-20.0f, 20.0f), s(0.3f, 1.5f);
  const int m = addMaterial(w.scene, diffuse(Color(0.5f)));
  const uint32_t mesh = addMesh(w.scene, octahedron(m));
  auto array = std::make_shared<InstanceArray>();
  array->name = "Scatter";
  array->firstObjectId = 1;
  for (uint32_t k = 0; k < kInstances; ++k) {
    Mat4 place = randomPlacement(rng).m;
    const float scale = s(rng) * 0.5f;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) place.m[r][c] *= scale;
      place.m[r][3] = u(rng);
    }
    const Transform t(place);
    w.toWorld.push_back(t.m);
    array->worldToObject.push_back(affineOf(t.inv));
  }
  Primitive p;
  p.kind = Primitive::Kind::kMesh;
  p.mesh = mesh;
  p.material = m;
  p.name = "Scatter";
  p.instances = array;
  w.scene.primitives.push_back(p);
  w.scene.finalize();
  return w;
}

/// Brute force: every triangle of every instance, in double (Möller & Trumbore 1997) on the
/// ray moved into the instance's object space by its stored matrix. `ambiguous` is set when the
/// answer could depend on rounding: the ray passes within `margin` of a triangle's edge (in
/// barycentrics), or two hits of different instances lie within a relative 1e-4 of each other.
struct Reference {
  bool hit = false;
  uint32_t instance = 0;
  double t = INFINITY;
  bool ambiguous = false;
};

Reference bruteForce(const World& w, const Ray& ray) {
  constexpr double kMargin = 1e-4;
  const TriangleMesh& mesh = w.scene.meshes[0];
  const InstanceArray& array = *w.scene.primitives[0].instances;
  Reference best;
  std::vector<std::pair<double, uint32_t>> hits;
  for (uint32_t k = 0; k < array.size(); ++k) {
    const Affine3& a = array.worldToObject[k];
    const Vec3 of = affinePoint(a, ray.o), df = affineVector(a, ray.d);
    const std::array<double, 3> o{of.x, of.y, of.z}, d{df.x, df.y, df.z};
    for (size_t t = 0; t < mesh.triangleCount(); ++t) {
      std::array<std::array<double, 3>, 3> v;
      for (int c = 0; c < 3; ++c) {
        const Vec3 p = mesh.positions[mesh.indices[3 * t + size_t(c)]];
        v[size_t(c)] = {p.x, p.y, p.z};
      }
      std::array<double, 3> e1, e2, s;
      for (int i = 0; i < 3; ++i) e1[i] = v[1][i] - v[0][i], e2[i] = v[2][i] - v[0][i];
      for (int i = 0; i < 3; ++i) s[i] = o[i] - v[0][i];
      const auto cross = [](const std::array<double, 3>& x, const std::array<double, 3>& y) {
        return std::array<double, 3>{x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2],
                                     x[0] * y[1] - x[1] * y[0]};
      };
      const auto dot = [](const std::array<double, 3>& x, const std::array<double, 3>& y) {
        return x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
      };
      const std::array<double, 3> pv = cross(d, e2), qv = cross(s, e1);
      const double det = dot(e1, pv);
      if (std::abs(det) < 1e-300) continue;
      const double b1 = dot(s, pv) / det, b2 = dot(d, qv) / det, tt = dot(e2, qv) / det;
      const double b0 = 1 - b1 - b2;
      const double inside = std::min({b0, b1, b2});
      if (inside < -kMargin || tt <= ray.tmin) continue;
      if (std::abs(tt - ray.tmax) <= 1e-4 * tt) best.ambiguous = true;  // at the ray's end
      if (tt >= ray.tmax) continue;
      if (inside < kMargin) {
        best.ambiguous = true;  // near an edge: either answer is right
        continue;
      }
      hits.push_back({tt, k});
    }
  }
  for (const auto& [t, k] : hits)
    if (t < best.t) best.t = t, best.instance = k, best.hit = true;
  for (const auto& [t, k] : hits)
    if (k != best.instance && std::abs(t - best.t) <= 1e-4 * best.t) best.ambiguous = true;
  return best;
}

/// Random rays: half aimed at a random instance's centre from anywhere in and around the
/// cube (hits), half in random directions (many misses); a fifth of them with a finite tmax.
std::vector<Ray> randomRays(const World& w, int n) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<float> u(-25.0f, 25.0f), unit(-1.0f, 1.0f), f(0.0f, 1.0f);
  std::uniform_int_distribution<uint32_t> pick(0, kInstances - 1);
  std::vector<Ray> rays;
  for (int i = 0; i < n; ++i) {
    Ray r;
    r.o = {u(rng), u(rng), u(rng)};
    if (i % 2 == 0) {
      const Mat4& m = w.toWorld[pick(rng)];
      r.d = Vec3(m.m[0][3], m.m[1][3], m.m[2][3]) - r.o;
    } else {
      r.d = {unit(rng), unit(rng), unit(rng)};
    }
    r.d = normalize(r.d);
    if (i % 5 == 4) r.tmax = 5.0f + 40.0f * f(rng);
    rays.push_back(r);
  }
  return rays;
}

TEST(InstanceArrayAccel, ClosestHitsAndOcclusionAreBruteForcesWithEitherAccelerator) {
  const World w = randomArray();
  const std::vector<Ray> rays = randomRays(w, 1200);
  std::vector<Reference> ref;
  for (const Ray& r : rays) ref.push_back(bruteForce(w, r));
  int compared = 0, hits = 0;
  for (const Reference& r : ref) compared += !r.ambiguous, hits += !r.ambiguous && r.hit;
  // Most rays have a clear answer, and many of those hit: the comparison means something.
  EXPECT_GT(compared, 1100);
  EXPECT_GT(hits, 500);
  for (const char* name : {"embree", "bvh"}) {
    const auto accel = makeAccelerator(name, w.scene);
    std::vector<Hit> batchHits(rays.size());
    std::vector<uint8_t> found(rays.size()), blocked(rays.size());
    accel->intersectBatch(rays, batchHits, found);
    accel->occludedBatch(rays, blocked);
    for (size_t i = 0; i < rays.size(); ++i) {
      if (ref[i].ambiguous) continue;
      Hit h;
      const bool any = accel->intersect(rays[i], h);
      ASSERT_EQ(any, ref[i].hit) << name << " ray " << i;
      EXPECT_EQ(bool(found[i]), ref[i].hit) << name << " batch ray " << i;
      EXPECT_EQ(accel->occluded(rays[i]), ref[i].hit) << name << " ray " << i;
      EXPECT_EQ(bool(blocked[i]), ref[i].hit) << name << " batch ray " << i;
      if (!ref[i].hit) continue;
      EXPECT_EQ(h.primitive, 0u) << name;
      EXPECT_EQ(h.instance, ref[i].instance) << name << " ray " << i;
      EXPECT_NEAR(h.t, ref[i].t, 1e-4 * ref[i].t) << name << " ray " << i;
      EXPECT_EQ(batchHits[i].instance, ref[i].instance) << name << " batch ray " << i;
      EXPECT_NEAR(batchHits[i].t, ref[i].t, 1e-4 * ref[i].t) << name << " batch ray " << i;
    }
  }
}

// The last-occluder cache of the in-house BVH names the blocking instance of a group (its
// `member`): shadow rays into an instance and into its neighbour in the group, each followed
// by one that stops short of everything, are answered right whatever the cache holds.
TEST(InstanceArrayAccel, OcclusionCacheNamesTheBlockingInstanceOfAGroup) {
  const World w = randomArray();
  const auto accel = makeAccelerator("bvh", w.scene);
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<uint32_t> pick(0, kInstances - 1);
  for (int i = 0; i < 200; ++i) {
    const uint32_t k = pick(rng);
    const Mat4& m = w.toWorld[k];
    const Vec3 c(m.m[0][3], m.m[1][3], m.m[2][3]);
    // Into the centre of instance k, then into the centre of its group neighbour, from 30 units
    // above: both blocked (by k, or by whatever lies in front).
    const uint32_t n = (k ^ 1u) < kInstances ? (k ^ 1u) : k;
    const Mat4& mn = w.toWorld[n];
    const Vec3 cn(mn.m[0][3], mn.m[1][3], mn.m[2][3]);
    for (const Vec3& target : {c, cn}) {
      Ray r;
      r.o = target + Vec3(0, 30, 0);
      r.d = Vec3(0, -1, 0);
      r.tmax = 30.0f;
      EXPECT_TRUE(accel->occluded(r)) << i;
      Ray past = r;  // stopping short of everything: nothing blocks it
      past.o = target + Vec3(0, 60, 0);
      past.tmax = 5.0f;
      EXPECT_FALSE(accel->occluded(past)) << i;
    }
  }
}

}  // namespace
}  // namespace tray
