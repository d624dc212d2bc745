// EXT_mesh_gpu_instancing (docs/instancing.md): the loader reads TRANSLATION, ROTATION and SCALE
// (each may be missing; normalized rotations; quantized translations with KHR_mesh_quantization)
// into one primitive per instance over one mesh; ids and names per instance; bad accessors give
// one line naming the file. scenes/instancing.gltf: Embree and the BVH give the same images,
// rays hit the instance they aim at, emissive instances are lights.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <vector>

#include "accel/registry.h"
#include "core/accelerator.h"
#include "core/error.h"
#include "film/cryptomatte.h"
#include "gltf/gltf_loader.h"
#include "integrators/registry.h"
#include "lights/light_set.h"
#include "render/prepared_scene.h"
#include "render/render_setup.h"
#include "render/renderer.h"
#include "tests/base64.h"
#include "tests/cli/cli_run.h"
#include "tests/film_difference.h"
#include "tests/temp_dir.h"

namespace tray {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const fs::path kScene = fs::path(TRAY_SOURCE_DIR) / "scenes" / "instancing.gltf";

/// A document under construction: one triangle mesh (node 0 "Grid", which gets the extension)
/// and a camera (node 1); accessors appended to one embedded buffer.
struct Doc {
  json doc;
  std::string bytes;

  Doc() {
    doc = json::parse(R"({
      "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 1]}],
      "extensionsUsed": ["EXT_mesh_gpu_instancing"],
      "nodes": [{"name": "Grid", "mesh": 0}, {"camera": 0, "translation": [0, 0, 5]}],
      "cameras": [{"type": "perspective",
                   "perspective": {"yfov": 0.8, "znear": 0.01, "aspectRatio": 1.0}}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
      "accessors": [], "bufferViews": []})");
    const float tri[9] = {-0.5f, -0.5f, 0, 0.5f, -0.5f, 0, 0, 0.5f, 0};
    add(tri, sizeof tri, 5126, "VEC3", 3);
    doc["accessors"][0]["min"] = {-0.5, -0.5, 0};
    doc["accessors"][0]["max"] = {0.5, 0.5, 0};
  }
  /// Appends an accessor over `size` bytes; returns its index.
  int add(const void* data, size_t size, int componentType, const char* type, size_t count,
          bool normalized = false) {
    while (bytes.size() % 4) bytes += '\0';
    json view = {{"buffer", 0}, {"byteOffset", bytes.size()}, {"byteLength", size}};
    bytes.append(static_cast<const char*>(data), size);
    doc["bufferViews"].push_back(view);
    json a = {{"bufferView", doc["bufferViews"].size() - 1},
              {"componentType", componentType},
              {"type", type},
              {"count", count}};
    if (normalized) a["normalized"] = true;
    doc["accessors"].push_back(a);
    return int(doc["accessors"].size() - 1);
  }
  void instance(const char* semantic, int accessor) {
    doc["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"][semantic] = accessor;
  }
  fs::path write() {
    static std::atomic<int> counter{0};
    doc["buffers"] = json::array();
    doc["buffers"].push_back(
        {{"byteLength", bytes.size()},
         {"uri", "data:application/octet-stream;base64," + test::base64(bytes)}});
    const fs::path dir = test::testDir() / ("doc" + std::to_string(counter++));
    fs::create_directories(dir);
    const fs::path file = dir / "instanced.gltf";
    std::ofstream(file) << doc.dump();
    return file;
  }
};

const float kT[9] = {1, 0, 0, 0, 2, 0, -3, 0, 1};
const float kS[9] = {1, 1, 1, 2, 2, 2, 0.5f, 1, 3};
/// Unit quaternions (x, y, z, w): identity, 90 degrees about z, 60 degrees about (1, 1, 0)/sqrt2.
const float kR[12] = {0,           0,           0,           1,           0, 0,
                      0.70710678f, 0.70710678f, 0.35355339f, 0.35355339f, 0, 0.8660254f};

Mat4 expected(const float* t, const float* r, const float* s, int k) {
  Mat4 m;
  if (t) m = m * Mat4::translate({t[3 * k], t[3 * k + 1], t[3 * k + 2]});
  if (r) m = m * Mat4::rotate(r[4 * k], r[4 * k + 1], r[4 * k + 2], r[4 * k + 3]);
  if (s) m = m * Mat4::scale({s[3 * k], s[3 * k + 1], s[3 * k + 2]});
  return m;
}

void expectNear(const Mat4& a, const Mat4& b, float tol) {
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) EXPECT_NEAR(a.m[i][j], b.m[i][j], tol) << i << "," << j;
}

std::string loadError(Doc& d) {
  const fs::path file = d.write();
  try {
    loadGltf(file.string());
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;  // one line
    EXPECT_EQ(message.rfind(file.string(), 0), 0u) << message;    // naming the file first
    return message;
  }
  return "";
}

TEST(GltfInstancing, ReadsTranslationRotationScale) {
  Doc d;
  d.instance("TRANSLATION", d.add(kT, sizeof kT, 5126, "VEC3", 3));
  d.instance("ROTATION", d.add(kR, sizeof kR, 5126, "VEC4", 3));
  d.instance("SCALE", d.add(kS, sizeof kS, 5126, "VEC3", 3));
  const Scene s = loadGltf(d.write().string());
  ASSERT_EQ(s.primitives.size(), 3u);
  EXPECT_EQ(s.meshes.size(), 1u);  // one mesh, placed three times: no copies
  for (int k = 0; k < 3; ++k) {
    const Primitive& p = s.primitives[size_t(k)];
    EXPECT_EQ(p.mesh, 0u);
    expectNear(p.toWorld.m, expected(kT, kR, kS, k), 1e-6f);
    EXPECT_EQ(p.objectId, 2 + k);  // after the document's 2 node indices
    EXPECT_EQ(p.name, "Grid#" + std::to_string(k));
  }
}

TEST(GltfInstancing, MissingAttributesAreTheIdentity) {
  for (const char* only : {"TRANSLATION", "ROTATION", "SCALE"}) {
    Doc d;
    const std::string o = only;
    if (o == "ROTATION")
      d.instance(only, d.add(kR, sizeof kR, 5126, "VEC4", 3));
    else
      d.instance(only, d.add(o == "SCALE" ? kS : kT, sizeof kT, 5126, "VEC3", 3));
    const Scene s = loadGltf(d.write().string());
    ASSERT_EQ(s.primitives.size(), 3u) << only;
    for (int k = 0; k < 3; ++k)
      expectNear(s.primitives[size_t(k)].toWorld.m,
                 expected(o == "TRANSLATION" ? kT : nullptr, o == "ROTATION" ? kR : nullptr,
                          o == "SCALE" ? kS : nullptr, k),
                 1e-6f);
  }
}

TEST(GltfInstancing, NodeTransformAppliesAfterTheInstances) {
  Doc d;
  d.instance("TRANSLATION", d.add(kT, sizeof kT, 5126, "VEC3", 3));
  d.doc["nodes"][0]["scale"] = {2, 2, 2};
  d.doc["nodes"][0]["translation"] = {0, 0, -1};
  const Scene s = loadGltf(d.write().string());
  ASSERT_EQ(s.primitives.size(), 3u);
  const Mat4 node = Mat4::translate({0, 0, -1}) * Mat4::scale({2, 2, 2});
  for (int k = 0; k < 3; ++k)
    expectNear(s.primitives[size_t(k)].toWorld.m, node * expected(kT, nullptr, nullptr, k), 1e-6f);
}

TEST(GltfInstancing, NormalizedRotationsAreDequantized) {
  for (int type : {5120, 5122}) {  // signed byte, signed short (glTF 2.0 §3.11)
    Doc d;
    std::vector<int8_t> b;
    std::vector<int16_t> h;
    for (float c : kR) {
      b.push_back(int8_t(std::lround(c * 127)));
      h.push_back(int16_t(std::lround(c * 32767)));
    }
    d.instance("ROTATION", type == 5120 ? d.add(b.data(), b.size(), type, "VEC4", 3, true)
                                        : d.add(h.data(), 2 * h.size(), type, "VEC4", 3, true));
    const Scene s = loadGltf(d.write().string());
    ASSERT_EQ(s.primitives.size(), 3u);
    for (int k = 0; k < 3; ++k)  // a byte's step is 1/127; renormalised
      expectNear(s.primitives[size_t(k)].toWorld.m, expected(nullptr, kR, nullptr, k),
                 type == 5120 ? 2e-2f : 1e-4f);
  }
}

TEST(GltfInstancing, QuantizedTranslationNeedsMeshQuantization) {
  const int8_t t[9] = {1, 0, 0, 0, 2, 0, -3, 0, 1};
  Doc d;
  d.instance("TRANSLATION", d.add(t, sizeof t, 5120, "VEC3", 3));
  EXPECT_NE(loadError(d).find("TRANSLATION"), std::string::npos);
  d.doc["extensionsUsed"].push_back("KHR_mesh_quantization");
  const Scene s = loadGltf(d.write().string());
  ASSERT_EQ(s.primitives.size(), 3u);
  for (int k = 0; k < 3; ++k)
    expectNear(s.primitives[size_t(k)].toWorld.m, expected(kT, nullptr, nullptr, k), 0);
}

TEST(GltfInstancing, BadAccessorsFailWithOneLine) {
  struct Case {
    const char* named;
    std::function<void(Doc&)> edit;
  };
  const std::vector<Case> cases = {
      {"different counts",
       [](Doc& d) {
         d.instance("TRANSLATION", d.add(kT, sizeof kT, 5126, "VEC3", 3));
         d.instance("SCALE", d.add(kS, 6 * sizeof(float), 5126, "VEC3", 2));
       }},
      {"TRANSLATION", [](Doc& d) { d.instance("TRANSLATION", d.add(kT, 8, 5126, "VEC2", 1)); }},
      {"ROTATION",  // unsigned normalized: the extension allows signed ones only
       [](Doc& d) {
         const uint16_t r[4] = {0, 0, 0, 65535};
         d.instance("ROTATION", d.add(r, sizeof r, 5123, "VEC4", 1, true));
       }},
      {"ROTATION",  // float VEC3: not a quaternion
       [](Doc& d) { d.instance("ROTATION", d.add(kT, sizeof kT, 5126, "VEC3", 3)); }},
      {"SCALE", [](Doc& d) { d.instance("SCALE", 99); }},
      {"at least one of TRANSLATION, ROTATION, SCALE",
       [](Doc& d) {
         d.doc["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"] = json::object();
       }},
      {"not a unit quaternion",
       [](Doc& d) {
         const float r[4] = {0, 0, 0, 0};
         d.instance("ROTATION", d.add(r, sizeof r, 5126, "VEC4", 1));
       }},
  };
  for (const Case& c : cases) {
    Doc d;
    c.edit(d);
    const std::string message = loadError(d);
    EXPECT_NE(message.find(c.named), std::string::npos) << c.named << ": " << message;
    EXPECT_NE(message.find("EXT_mesh_gpu_instancing"), std::string::npos) << message;
  }
}

TEST(GltfInstancing, ZeroScaleInstancesAreSkippedWithAWarning) {
  Doc d;
  const float s[9] = {1, 1, 1, 0, 0, 0, 1, 1, 1};
  d.instance("SCALE", d.add(s, sizeof s, 5126, "VEC3", 3));
  LoadReport report;
  const Scene scene = loadGltf(d.write().string(), {}, &report);
  ASSERT_EQ(scene.primitives.size(), 2u);
  EXPECT_EQ(scene.primitives[1].name, "Grid#2");  // instance 2 keeps its id and name
  EXPECT_EQ(scene.primitives[1].objectId, 4);
  bool warned = false;
  for (const auto& w : report.warnings) warned |= w.find("zero-scale") != std::string::npos;
  EXPECT_TRUE(warned);
}

TEST(GltfInstancing, StaticInstancesStayPutUnderMotionBlur) {
  Doc d;
  d.instance("TRANSLATION", d.add(kT, sizeof kT, 5126, "VEC3", 3));
  d.instance("ROTATION", d.add(kR, sizeof kR, 5126, "VEC4", 3));
  d.doc["nodes"][0]["translation"] = {0, 1, 0};
  LoadOptions o;
  o.time = 0.0f;
  o.shutterOpen = 0, o.shutterClose = 0.5f, o.motionSteps = 3;
  o.previousTime = -0.04f;
  const Scene s = loadGltf(d.write().string(), o);
  ASSERT_EQ(s.primitives.size(), 3u);
  ASSERT_EQ(s.previousToWorld.size(), 3u);
  for (int k = 0; k < 3; ++k) {
    const Primitive& p = s.primitives[size_t(k)];
    EXPECT_TRUE(p.motion.empty());
    const Mat4 m = Mat4::translate({0, 1, 0}) * expected(kT, kR, nullptr, k);
    expectNear(p.toWorld.m, m, 1e-6f);
    expectNear(s.previousToWorld[size_t(k)], m, 1e-6f);
  }
}

// --- scenes/instancing.gltf ------------------------------------------------------------------

TEST(GltfInstancing, TestSceneHasEveryInstanceWithItsOwnId) {
  const Scene s = loadGltf(kScene.string());
  EXPECT_EQ(s.meshes.size(), 3u);  // balls, lamps, floor: stored once each
  EXPECT_EQ(s.primitives.size(), 125u + 4 + 1);
  std::set<int> ids;
  std::set<std::string> names;
  for (const Primitive& p : s.primitives) {
    ids.insert(p.objectId);
    names.insert(cryptomatteObjectName(p));
  }
  EXPECT_EQ(ids.size(), s.primitives.size());
  EXPECT_EQ(names.size(), s.primitives.size());
  EXPECT_TRUE(names.count("Balls#0") && names.count("Balls#124") && names.count("Lamps#3"));
}

TEST(GltfInstancing, RaysHitTheInstanceTheyAimAtWithEitherAccelerator) {
  const Scene s = loadGltf(kScene.string());
  for (const char* accel : {"embree", "bvh"}) {
    const auto a = makeAccelerator(accel, s);
    int aimed = 0;
    for (uint32_t i = 0; i < s.primitives.size(); ++i) {
      const Primitive& p = s.primitives[i];
      if (p.name.rfind("Balls#", 0) != 0) continue;
      // From just outside the sphere's top (radius <= 0.18) straight down to its centre.
      const Vec3 c = p.toWorld.point(Vec3(0.0f));
      Ray ray{c + Vec3(0, 0.2f, 0), Vec3(0, -1, 0)};
      Hit h;
      ASSERT_TRUE(a->intersect(ray, h)) << accel << " " << p.name;
      EXPECT_EQ(h.primitive, i) << accel << " " << p.name;
      // The surface point is on the placed sphere, and its geometric normal is the facet's
      // object-space normal by the inverse transpose (the instances scale non-uniformly).
      const SurfacePoint sp = s.surface(ray, h);
      const Vec3 local = p.toWorld.inversePoint(sp.p);
      // On the 12-segment sphere: a facet lies inside by up to 1 - cos^2(15 deg) = 0.067.
      EXPECT_NEAR(length(local), 1.0f, 0.07f) << p.name;
      const TriangleMesh& m = s.meshes[p.mesh];
      const uint32_t* v = &m.indices[3 * h.triangle];
      const Vec3 facet =
          cross(m.positions[v[1]] - m.positions[v[0]], m.positions[v[2]] - m.positions[v[0]]);
      EXPECT_NEAR(std::fabs(dot(sp.ng, normalize(p.toWorld.normal(facet)))), 1.0f, 1e-4f) << p.name;
      ++aimed;
    }
    EXPECT_EQ(aimed, 125);
  }
}

TEST(GltfInstancing, EmissiveInstancesAreLights) {
  const Scene s = loadGltf(kScene.string());
  size_t lampTriangles = 0;
  for (const Primitive& p : s.primitives)
    if (p.name.rfind("Lamps#", 0) == 0) lampTriangles += s.meshes[p.mesh].triangleCount();
  EXPECT_GT(lampTriangles, 0u);
  const LightSet lights(s);
  // Every lamp instance's triangles, at its own place, and the one point light.
  EXPECT_EQ(lights.size(), lampTriangles + 1);
}

Film render(const Scene& scene, const std::string& accel, const char* integrator) {
  const CameraDesc cam = chooseCamera(scene, -1);
  const PreparedScene prepared(scene, cam, {96, 64}, accel);
  RenderSettings settings;
  settings.set("integrator", integrator);
  settings.set("spp", 4);
  const RenderContext ctx = prepared.context(settings);
  auto integrator_ = makeIntegrator(ctx);
  Film film(96, 64);
  renderImage(*integrator_, film);
  return film;
}

/// As tests/accel/bvh_render_test.cpp: whitted within RMSE 1e-5 and 1e-3 per value (the
/// triangle tests differ in the last bits), path in mean within 0.1%.
TEST(GltfInstancing, EmbreeAndBvhGiveTheSameImages) {
  const Scene scene = loadGltf(kScene.string());
  for (const char* integrator : {"whitted", "path"}) {
    const Film a = render(scene, "embree", integrator), b = render(scene, "bvh", integrator);
    const test::FilmDifference d = test::filmDifference(a, b);
    EXPECT_GT(d.meanA, 1e-3) << integrator;  // not black
    if (std::string(integrator) == "whitted") {
      EXPECT_LE(d.rmse, 1e-5) << integrator;
      EXPECT_LE(d.maxAbs, 1e-3) << integrator;
    } else {
      EXPECT_LE(std::fabs(d.meanA - d.meanB), 1e-3 * d.meanB) << integrator;
    }
  }
}

/// --max-memory counts placements, not only triangles: 20000 instances of one triangle need
/// about 14 MB as one primitive each (io/memory_estimate.h's kBytesPerPlacement, tray-render
/// --instance-arrays 0), which 10 MB refuses; as an instance array (the default from 1024
/// instances, kBytesPerArrayInstance) about 3 MB, which it takes.
TEST(GltfInstancing, MaxMemoryCountsInstances) {
  Doc d;
  std::vector<float> t;
  for (int k = 0; k < 20000; ++k) t.insert(t.end(), {float(k % 100), float(k / 100), -10.0f});
  d.instance("TRANSLATION", d.add(t.data(), 4 * t.size(), 5126, "VEC3", 20000));
  const fs::path file = d.write(), dir = file.parent_path();
  const test::CliResult r = test::runCli(
      TRAY_RENDER_BIN,
      test::quoted(file) + " --resolution 8x6 --instance-arrays 0 --max-memory 10 -o " +
          test::quoted(dir / "x.exr"),
      dir);
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_NE(r.err.find("geometry 14 MB"), std::string::npos) << r.err;
  const test::CliResult ok = test::runCli(
      TRAY_RENDER_BIN,
      test::quoted(file) + " --resolution 8x6 --instance-arrays 0 --max-memory 40 -o " +
          test::quoted(dir / "x.exr"),
      dir);
  EXPECT_EQ(ok.exitCode, 0) << ok.err;
  const test::CliResult array = test::runCli(
      TRAY_RENDER_BIN,
      test::quoted(file) + " --resolution 8x6 --max-memory 10 -o " + test::quoted(dir / "x.exr"),
      dir);
  EXPECT_EQ(array.exitCode, 0) << array.err;
}

}  // namespace
}  // namespace tray
