#include "shapes/mesh_solid.h"

#include <gtest/gtest.h>

#include <random>

#include "accel/registry.h"
#include "core/error.h"
#include "gltf/gltf_loader.h"
#include "shapes/box.h"
#include "tests/shapes/solid_meshes.h"

namespace tray {
namespace {

using namespace tray::test;

Ray line(Vec3 o, Vec3 d) {
  return Ray{o, d, 0.0f, kInfinity};
}

TEST(MeshSolid, CubeMeshHasTheIntervalsOfTheAnalyticBox) {
  MeshSolid mesh(boxMesh(Vec3(-1.0f), Vec3(1.0f)), acceleratorFactory("embree"));
  Box box;
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.5f, 1.5f);
  int twoSided = 0, behind = 0;
  for (int i = 0; i < 500; ++i) {
    // Origins before, inside and beyond the cube: intervals cover the whole line.
    Vec3 o{u(rng) * 2, u(rng) * 2, u(rng) * 2}, target{u(rng), u(rng), u(rng)};
    Ray r = line(o, target - o);
    std::vector<Interval> a, b;
    mesh.intervals(r, a);
    box.intervals(r, b);
    ASSERT_EQ(a.size(), b.size()) << i;
    if (a.empty()) continue;
    EXPECT_NEAR(a[0].enter.t, b[0].enter.t, 1e-5f);
    EXPECT_NEAR(a[0].exit.t, b[0].exit.t, 1e-5f);
    EXPECT_GT(dot(normalize(a[0].enter.normal), b[0].enter.normal), 0.99999f);
    EXPECT_GT(dot(normalize(a[0].exit.normal), b[0].exit.normal), 0.99999f);
    ++twoSided;
    behind += a[0].enter.t < 0;
  }
  EXPECT_GT(twoSided, 300);
  EXPECT_GT(behind, 10);  // entries behind the origin came from the backwards query
}

TEST(MeshSolid, RaysThroughSharedEdgesAndVerticesGiveOneInterval) {
  MeshSolid mesh(boxMesh(Vec3(-1.0f), Vec3(1.0f)), acceleratorFactory("embree"));
  // Each face is two triangles sharing a diagonal; these rays cross diagonals, edges, corners.
  for (Ray r :
       {line({-5, -5, 0}, {1, 1, 0}), line({-5, -5, -5}, {1, 1, 1}), line({0, 0, -5}, {0, 0, 1}),
        line({0.3f, 0.3f, -5}, {0, 0, 1}), line({-1, 0, -5}, {0, 0, 1})}) {
    std::vector<Interval> spans;
    mesh.intervals(r, spans);
    ASSERT_EQ(spans.size(), 1u) << r.d.x << r.d.y << r.d.z;
    EXPECT_LT(spans[0].enter.t, spans[0].exit.t);
  }
}

TEST(MeshSolid, TorusHasTwoIntervalsAcrossAndNoneThroughTheHole) {
  MeshSolid torus(torusMesh(1.0f, 0.3f, 64, 32), acceleratorFactory("embree"));
  std::vector<Interval> spans;
  torus.intervals(line({-3, 0.01f, 0.01f}, {1, 0, 0}), spans);
  ASSERT_EQ(spans.size(), 2u);
  EXPECT_NEAR(spans[0].enter.t, 3 - 1.3f, 2e-3f);
  EXPECT_NEAR(spans[0].exit.t, 3 - 0.7f, 2e-3f);
  EXPECT_NEAR(spans[1].enter.t, 3 + 0.7f, 2e-3f);
  EXPECT_NEAR(spans[1].exit.t, 3 + 1.3f, 2e-3f);
  // Entering against the outward normal: -x on the outer rim, and -x on the hole side too
  // (the inner wall faces the axis); leaving the inner wall on the near side: +x.
  EXPECT_LT(normalize(spans[0].enter.normal).x, -0.99f);
  EXPECT_GT(normalize(spans[0].exit.normal).x, 0.99f);
  EXPECT_LT(normalize(spans[1].enter.normal).x, -0.99f);
  spans.clear();
  torus.intervals(line({0, -3, 0}, {0, 1, 0}), spans);
  EXPECT_TRUE(spans.empty());
  Hit h;  // nearest crossing from inside the tube: its exit
  ASSERT_TRUE(torus.intersect(line({1, 0, 0.001f}, {0, 1, 0}), h));
  EXPECT_NEAR(h.t, 0.3f, 2e-3f);
  EXPECT_GT(h.normal.y, 0);
}

TEST(MeshSolid, KhronosBoxWithPerFaceVerticesIsAClosedSolid) {
  // Box.glb duplicates its 8 corners into 24 vertices (hard edges): welding makes it closed.
  Scene scene = loadGltf(std::string(TRAY_SHARED_DIR) + "/gltf-samples/Box.glb");
  ASSERT_EQ(scene.meshes.size(), 1u);
  EXPECT_EQ(scene.meshes[0].positions.size(), 24u);
  MeshSolid solid(scene.meshes[0], acceleratorFactory("embree"));
  Box box(Vec3(-0.5f), Vec3(0.5f));
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  int hits = 0;
  for (int i = 0; i < 200; ++i) {
    Vec3 o{3 * u(rng), 3 * u(rng), 3 * u(rng)}, target{0.6f * u(rng), 0.6f * u(rng), 0.6f * u(rng)};
    std::vector<Interval> a, b;
    solid.intervals(line(o, target - o), a);
    box.intervals(line(o, target - o), b);
    ASSERT_EQ(a.size(), b.size());
    if (a.empty()) continue;
    ++hits;
    EXPECT_NEAR(a[0].enter.t, b[0].enter.t, 1e-5f);
    EXPECT_NEAR(a[0].exit.t, b[0].exit.t, 1e-5f);
  }
  EXPECT_GT(hits, 100);
}

TEST(MeshSolid, InwardWoundMeshIsTurnedOutward) {
  TriangleMesh m = boxMesh(Vec3(-1.0f), Vec3(1.0f));
  for (size_t t = 0; t < m.triangleCount(); ++t)
    std::swap(m.indices[3 * t + 1], m.indices[3 * t + 2]);
  MeshSolid solid(m, acceleratorFactory("embree"));
  std::vector<Interval> spans;
  solid.intervals(line({0, 0, -5}, {0, 0, 1}), spans);
  ASSERT_EQ(spans.size(), 1u);
  EXPECT_FLOAT_EQ(spans[0].enter.t, 4.0f);
  EXPECT_LT(spans[0].enter.normal.z, 0);
}

TEST(MeshSolid, OpenOrEmptyMeshesAreRejectedByName) {
  TriangleMesh open = boxMesh(Vec3(-1.0f), Vec3(1.0f));
  open.name = "lid";
  open.indices.resize(open.indices.size() - 6);  // drop one face
  try {
    MeshSolid s(open, acceleratorFactory("embree"));
    FAIL() << "accepted an open mesh";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("mesh 'lid' used as a CSG solid is not closed"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(MeshSolid(TriangleMesh{}, acceleratorFactory("embree")), Error);
  // Vertices duplicated per face (as glTF exports hard edges) still weld into a closed solid.
  EXPECT_NO_THROW(MeshSolid(boxMesh(Vec3(0.0f), Vec3(1.0f)), acceleratorFactory("embree")));
}

}  // namespace
}  // namespace tray
