// Instance arrays (core/instance_array.h, docs/instancing.md): scenes/instancing.gltf loaded with
// its 125 balls as one instance array (LoadOptions::instanceArrayMin 1) renders as the same
// scene with one Primitive per instance, with Embree and the BVH; every instance keeps its id
// and name (objectid AOV, Cryptomatte); a hit names its instance and Scene::placement gives its
// transform; what must not become an array (emissive meshes, motion, alpha, few instances)
// stays one Primitive per instance.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "accel/registry.h"
#include "core/accelerator.h"
#include "core/error.h"
#include "gltf/gltf_loader.h"
#include "integrators/registry.h"
#include "render/prepared_scene.h"
#include "render/render_setup.h"
#include "render/renderer.h"
#include "tests/base64.h"
#include "tests/cli/cli_run.h"
#include "tests/exr_read.h"
#include "tests/film_difference.h"
#include "tests/render_film.h"
#include "tests/temp_dir.h"

namespace tray {
namespace {

namespace fs = std::filesystem;

const fs::path kScene = fs::path(TRAY_SOURCE_DIR) / "scenes" / "instancing.gltf";

Scene load(size_t arrayMin) {
  LoadOptions o;
  o.instanceArrayMin = arrayMin;
  return loadGltf(kScene.string(), o);
}

/// The instance array of `s` (its only one) or kNoPrimitive.
uint32_t arrayOf(const Scene& s) {
  uint32_t found = kNoPrimitive;
  for (uint32_t i = 0; i < s.primitives.size(); ++i)
    if (s.primitives[i].instances) {
      EXPECT_EQ(found, kNoPrimitive);
      found = i;
    }
  return found;
}

void expectNear(const Mat4& a, const Mat4& b, float tol, const std::string& what) {
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) EXPECT_NEAR(a.m[i][j], b.m[i][j], tol) << what << " " << i << j;
}

TEST(InstanceArray, BallsBecomeOneArrayLampsStayPerInstance) {
  const Scene perInstance = load(0), arrays = load(1);
  EXPECT_EQ(perInstance.primitives.size(), 125u + 4 + 1);
  // The 125 balls are one primitive; the 4 emissive lamps fall back (lights are per instance);
  // the floor is no instance.
  ASSERT_EQ(arrays.primitives.size(), 1u + 4 + 1);
  const uint32_t a = arrayOf(arrays);
  ASSERT_NE(a, kNoPrimitive);
  EXPECT_EQ(arrays.primitives[a].instanceCount(), 125u);
  int lamps = 0;
  for (const Primitive& p : arrays.primitives) lamps += p.name.rfind("Lamps#", 0) == 0;
  EXPECT_EQ(lamps, 4);
  // Below the threshold (the default 1024) nothing is an array.
  EXPECT_EQ(arrayOf(load(kInstanceArrayMinInstances)), kNoPrimitive);
}

TEST(InstanceArray, EveryInstanceKeepsItsPlacementIdAndName) {
  const Scene perInstance = load(0), arrays = load(1);
  const uint32_t a = arrayOf(arrays);
  ASSERT_NE(a, kNoPrimitive);
  uint32_t k = 0;
  for (uint32_t i = 0; i < perInstance.primitives.size(); ++i) {
    const Primitive& p = perInstance.primitives[i];
    if (p.name.rfind("Balls#", 0) != 0) continue;
    ASSERT_LT(k, arrays.primitives[a].instanceCount());
    EXPECT_EQ(arrays.objectId(a, k), p.objectId) << p.name;
    EXPECT_EQ(arrays.objectName(a, k), p.name);
    Transform scratch;
    const Transform& t = arrays.placement(a, k, scratch);
    expectNear(t.m, p.toWorld.m, 1e-5f, p.name);
    expectNear(t.inv, p.toWorld.inv, 1e-4f, p.name);
    ++k;
  }
  EXPECT_EQ(k, 125u);
  // Other primitives keep their own.
  for (uint32_t i = 0; i < arrays.primitives.size(); ++i) {
    if (arrays.primitives[i].instances) continue;
    EXPECT_EQ(arrays.objectId(i, 0), arrays.primitives[i].objectId);
  }
}

// As GltfInstancing.RaysHitTheInstanceTheyAimAtWithEitherAccelerator, through the array: the hit
// names the array and the instance, the surface is on that instance, single rays, batches and
// all-hits queries agree.
TEST(InstanceArray, RaysHitTheInstanceTheyAimAt) {
  const Scene perInstance = load(0), arrays = load(1);
  const uint32_t a = arrayOf(arrays);
  ASSERT_NE(a, kNoPrimitive);
  for (const char* name : {"embree", "bvh"}) {
    const auto accel = makeAccelerator(name, arrays);
    std::vector<Ray> rays;
    std::vector<uint32_t> aimed;
    uint32_t k = 0;
    for (const Primitive& p : perInstance.primitives) {
      if (p.name.rfind("Balls#", 0) != 0) continue;
      const Vec3 c = p.toWorld.point(Vec3(0.0f));
      const Ray ray{c + Vec3(0, 0.2f, 0), Vec3(0, -1, 0)};
      Hit h;
      ASSERT_TRUE(accel->intersect(ray, h)) << name << " " << p.name;
      EXPECT_EQ(h.primitive, a) << name << " " << p.name;
      EXPECT_EQ(h.instance, k) << name << " " << p.name;
      const SurfacePoint sp = arrays.surface(ray, h);
      EXPECT_EQ(sp.instance, k);
      EXPECT_NEAR(length(p.toWorld.inversePoint(sp.p)), 1.0f, 0.07f) << p.name;
      std::vector<Hit> all;
      accel->allHits(ray, all);
      ASSERT_FALSE(all.empty()) << name;
      EXPECT_EQ(all[0].primitive, a);
      EXPECT_EQ(all[0].instance, k) << name << " " << p.name;
      EXPECT_TRUE(accel->occluded(ray));
      rays.push_back(ray);
      aimed.push_back(k++);
    }
    ASSERT_EQ(k, 125u);
    std::vector<Hit> hits(rays.size());
    std::vector<uint8_t> found(rays.size()), blocked(rays.size());
    accel->intersectBatch(rays, hits, found);
    accel->occludedBatch(rays, blocked);
    for (size_t r = 0; r < rays.size(); ++r) {
      EXPECT_TRUE(found[r] && blocked[r]) << name << " " << r;
      EXPECT_EQ(hits[r].primitive, a) << name;
      EXPECT_EQ(hits[r].instance, aimed[r]) << name;
    }
  }
}

Film render(const Scene& scene, const std::string& accel, const char* integrator) {
  RenderSettings settings;
  settings.set("integrator", integrator);
  settings.set("spp", 4);
  return test::renderFilm(scene, chooseCamera(scene, -1), 96, 64, settings, nullptr, {}, accel);
}

/// The array renders as the per-instance primitives do, with either accelerator, and the two
/// accelerators agree on the array: whitted within RMSE 2e-4 (object-space rays from the stored
/// inverse, not Embree's own, differ in the last bits, as tests/accel/bvh_render_test.cpp's
/// accelerators do), path in mean within 0.5%.
TEST(InstanceArray, RendersAsThePerInstancePrimitives) {
  const Scene perInstance = load(0), arrays = load(1);
  for (const char* integrator : {"whitted", "path"}) {
    const Film bvhArray = render(arrays, "bvh", integrator);
    for (const char* accel : {"embree", "bvh"}) {
      const Film old = render(perInstance, accel, integrator);
      const Film array = render(arrays, accel, integrator);
      for (const test::FilmDifference& d :
           {test::filmDifference(array, old), test::filmDifference(array, bvhArray)}) {
        EXPECT_GT(d.meanA, 1e-3) << accel << " " << integrator;
        if (std::string(integrator) == "whitted")
          EXPECT_LE(d.rmse, 2e-4) << accel << " " << integrator;
        else
          EXPECT_LE(std::fabs(d.meanA - d.meanB), 5e-3 * d.meanB) << accel << " " << integrator;
      }
    }
  }
}

/// tray-render --instance-arrays: the objectid layer and the Cryptomatte manifest are the
/// per-instance ones (ids of the array's instances as the instances' own).
TEST(InstanceArray, ObjectIdsAndCryptomatteAreTheInstancesOwn) {
  const fs::path dir = test::testDir();
  test::Exr exr[2];
  for (int arrays : {0, 1}) {
    const fs::path out = dir / ("ids" + std::to_string(arrays) + ".exr");
    const test::CliResult r = test::runCli(
        TRAY_RENDER_BIN,
        test::quoted(kScene) + " --resolution 96x64 --spp 1 --integrator whitted --float " +
            "--aov objectid,crypto_object --instance-arrays " + std::to_string(arrays) + " -o " +
            test::quoted(out),
        dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    exr[arrays] = test::readExrFile(out);
  }
  ASSERT_GE(exr[0].channel("objectid.id"), 0);
  int same = 0, balls = 0;
  std::set<float> ids;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 96; ++x) {
      const float a = exr[0].at(x, y, "objectid.id"), b = exr[1].at(x, y, "objectid.id");
      same += a == b;
      ids.insert(b);
    }
  for (float id : ids) balls += id >= 0;
  EXPECT_GE(same, 96 * 64 * 99 / 100);  // edges may differ in the last bits of a ray
  EXPECT_GT(balls, 20);                 // many instances, each its own id
  int manifests = 0;
  for (const auto& attr : exr[0].spec.extra_attribs) {
    const std::string name = attr.name().string();
    if (name.find("manifest") == std::string::npos) continue;
    ++manifests;
    EXPECT_EQ(exr[1].spec.get_string_attribute(name), exr[0].spec.get_string_attribute(name));
  }
  EXPECT_EQ(manifests, 1);
}

/// A triangle (node 0, "Row") instanced `count` times along x by TRANSLATION and SCALE (instance
/// `hidden` at zero scale, -1: none), its material's alphaMode `alpha`.
fs::path rowOfTriangles(int count, int hidden, const char* alpha) {
  std::string bytes;
  auto append = [&](const std::vector<float>& v) {
    const size_t at = bytes.size();
    bytes.append(reinterpret_cast<const char*>(v.data()), 4 * v.size());
    return at;
  };
  std::vector<float> t, s;
  for (int k = 0; k < count; ++k) {
    t.insert(t.end(), {float(k), 0, 0});
    const float scale = k == hidden ? 0.0f : 0.4f;
    s.insert(s.end(), {scale, scale, scale});
  }
  const size_t tri = append({-1, -1, 0, 1, -1, 0, 0, 1, 0}), tAt = append(t), sAt = append(s);
  nlohmann::json doc = nlohmann::json::parse(R"({
      "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
      "extensionsUsed": ["EXT_mesh_gpu_instancing"],
      "nodes": [{"name": "Row", "mesh": 0, "extensions": {"EXT_mesh_gpu_instancing":
                 {"attributes": {"TRANSLATION": 1, "SCALE": 2}}}}],
      "materials": [{}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "material": 0}]}],
      "accessors": [
        {"bufferView": 0, "componentType": 5126, "type": "VEC3", "count": 3,
         "min": [-1, -1, 0], "max": [1, 1, 0]},
        {"bufferView": 1, "componentType": 5126, "type": "VEC3"},
        {"bufferView": 2, "componentType": 5126, "type": "VEC3"}]})");
  doc["materials"][0]["alphaMode"] = alpha;
  doc["accessors"][1]["count"] = count;
  doc["accessors"][2]["count"] = count;
  doc["bufferViews"] = nlohmann::json::array();
  for (auto [at, length] :
       {std::pair{tri, size_t(36)}, {tAt, 12 * size_t(count)}, {sAt, 12 * size_t(count)}})
    doc["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", at}, {"byteLength", length}});
  doc["buffers"] = nlohmann::json::array();
  doc["buffers"].push_back(
      {{"byteLength", bytes.size()},
       {"uri", "data:application/octet-stream;base64," + test::base64(bytes)}});
  static int counter = 0;
  const fs::path dir = test::testDir() / ("row" + std::to_string(counter++));
  fs::create_directories(dir);
  std::ofstream(dir / "row.gltf") << doc.dump();
  return dir / "row.gltf";
}

TEST(InstanceArray, NonOpaqueMeshesKeepOnePrimitivePerInstance) {
  LoadOptions o;
  o.instanceArrayMin = 1;
  for (const char* alpha : {"BLEND", "MASK"}) {
    const Scene s = loadGltf(rowOfTriangles(8, -1, alpha).string(), o);
    EXPECT_EQ(arrayOf(s), kNoPrimitive) << alpha;
    EXPECT_EQ(s.primitives.size(), 8u) << alpha;
  }
  const Scene opaque = loadGltf(rowOfTriangles(8, -1, "OPAQUE").string(), o);
  ASSERT_EQ(opaque.primitives.size(), 1u);
  EXPECT_EQ(opaque.primitives[0].instanceCount(), 8u);
}

// A zero-scale instance is skipped, its id and name unused, as one primitive per instance does;
// the others keep theirs, and rays find them.
TEST(InstanceArray, ZeroScaleInstancesKeepTheOthersIds) {
  LoadOptions o;
  o.instanceArrayMin = 1;
  const fs::path file = rowOfTriangles(6, 2, "OPAQUE");
  const Scene array = loadGltf(file.string(), o);
  o.instanceArrayMin = 0;
  const Scene perInstance = loadGltf(file.string(), o);
  ASSERT_EQ(perInstance.primitives.size(), 5u);
  ASSERT_EQ(array.primitives.size(), 1u);
  ASSERT_EQ(array.primitives[0].instanceCount(), 5u);
  for (uint32_t k = 0; k < 5; ++k) {
    EXPECT_EQ(array.objectId(0, k), perInstance.primitives[k].objectId);
    EXPECT_EQ(array.objectName(0, k), perInstance.primitives[k].name);
  }
  EXPECT_EQ(array.objectName(0, 2), "Row#3");
  for (const char* name : {"embree", "bvh"}) {
    const auto accel = makeAccelerator(name, array);
    for (int x : {0, 1, 3, 4, 5}) {
      Hit h;
      ASSERT_TRUE(accel->intersect(Ray{{float(x), 0, 5}, {0, 0, -1}}, h)) << name << " " << x;
      EXPECT_EQ(array.objectName(0, h.instance), "Row#" + std::to_string(x)) << name;
    }
    Hit h;
    EXPECT_FALSE(accel->intersect(Ray{{2, 0, 5}, {0, 0, -1}}, h)) << name;
  }
}

TEST(InstanceArray, MotionKeepsOnePrimitivePerInstance) {
  LoadOptions o;
  o.instanceArrayMin = 1;
  o.time = 0.0f;
  o.previousTime = -0.04f;  // --aov motion
  EXPECT_EQ(arrayOf(loadGltf(kScene.string(), o)), kNoPrimitive);
  o.previousTime.reset();
  o.shutterOpen = 0, o.shutterClose = 0.02f, o.motionSteps = 2;  // --shutter
  EXPECT_EQ(arrayOf(loadGltf(kScene.string(), o)), kNoPrimitive);
}

TEST(InstanceArray, SceneRefusesAnEmissiveOrMovingArray) {
  Scene s = load(1);
  const uint32_t a = arrayOf(s);
  ASSERT_NE(a, kNoPrimitive);
  Scene emissive = s;
  Material m = emissive.materials[size_t(emissive.meshes[emissive.primitives[a].mesh].material)];
  m.emissive = {1, 1, 1};
  emissive.materials.push_back(m);
  emissive.meshes[emissive.primitives[a].mesh].material = int(emissive.materials.size() - 1);
  EXPECT_THROW(emissive.finalize(), Error);
  Scene moving = s;
  moving.primitives[a].motion = {Mat4(), Mat4()};
  EXPECT_THROW(moving.finalize(), Error);
}

}  // namespace
}  // namespace tray
