// Stability 7: meshes with zero-area triangles (collinear vertices, a repeated index, duplicate
// vertices at one position, a sliver whose area underflows) and NaN normals. The glTF loader
// drops the triangles and zeroes the normals, with one warning line per kind carrying the count;
// scenes built in code keep them, and neither accelerator ever hits a zero-area triangle while
// Scene::surface falls back to the geometric normal where the interpolated one is not finite.
// Either way: no NaN pixel, and the image is that of the clean mesh.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "accel/registry.h"
#include "gltf/gltf_loader.h"
#include "tests/integrators/path_under_test.h"
#include "tests/stability/stability_scenes.h"
#include "tests/temp_dir.h"

namespace tray {
namespace {

using namespace tray::stability;
namespace fs = std::filesystem;

constexpr int kW = 64, kH = 48;
constexpr size_t kBadTriangles = 5;

/// Appends the zero-area triangles, most in front of the sphere where the camera looks.
void addBadTriangles(TriangleMesh& m) {
  auto vertex = [&](const Vec3& p) {
    m.positions.push_back(p);
    if (!m.normals.empty()) m.normals.push_back(Vec3(0, 0, 1));
    return uint32_t(m.positions.size() - 1);
  };
  const uint32_t a = vertex({-0.8f, 0.1f, 1.3f}), b = vertex({0, 0.1f, 1.3f}),
                 c = vertex({0.8f, 0.1f, 1.3f});
  const uint32_t d = vertex({0, -0.3f, 1.3f}), d2 = vertex({0, -0.3f, 1.3f}),
                 d3 = vertex({0, -0.3f, 1.3f});
  // Distinct vertices 1e-20 apart (inside the sphere): the area, 1e-40, squares to 0 in float.
  const uint32_t s = vertex({1e-20f, 0, 0}), s1 = vertex({2e-20f, 0, 0}),
                 s2 = vertex({1e-20f, 1e-20f, 0});
  m.indices.insert(m.indices.end(), {a, b, c,      // collinear
                                     a, a, c,      // a repeated index
                                     d, d2, d3,    // three duplicate vertices: a point
                                     d, d2, c,     // two duplicates and another vertex
                                     s, s1, s2});  // a sliver: its cross product underflows to 0
}

struct Render {
  Film film;
  RenderStats stats;
};

Render render(const SceneWithCamera& a, const char* integrator, const char* accel) {
  RenderSettings st;
  st.set("integrator", test::orPathUnderTest(integrator));
  st.set("spp", 4);
  st.set("pixel-sampler", "jitter");
  RenderStats stats;
  Film f = renderFilm(a.scene, a.camera, kW, kH, st, &stats, {}, accel);
  return {std::move(f), stats};
}

size_t nonFinitePixels(const Film& f) {
  size_t n = 0;
  for (int y = 0; y < f.height(); ++y)
    for (int x = 0; x < f.width(); ++x)
      for (int c = 0; c < 4; ++c) n += std::isfinite(f.pixel(Film::kBeauty, x, y)[c]) ? 0 : 1;
  return n;
}

/// Pixels whose RGB differs by more than `tolerance` in some channel.
size_t differingPixels(const Film& a, const Film& b, float tolerance) {
  size_t n = 0;
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x) {
      bool differs = false;
      for (int c = 0; c < 3; ++c)
        differs = differs || std::fabs(a.pixel(Film::kBeauty, x, y)[c] -
                                       b.pixel(Film::kBeauty, x, y)[c]) > tolerance;
      n += differs;
    }
  return n;
}

// --- Scenes built in code: nothing drops the bad data ----------------------------------------

struct Method {
  const char* integrator;
  const char* accel;
};

class CodeBuiltMesh : public ::testing::TestWithParam<Method> {};

TEST_P(CodeBuiltMesh, ZeroAreaTrianglesAreNeverHit) {
  const Method m = GetParam();
  TriangleMesh bad = smoothSphere();
  addBadTriangles(bad);
  const Render clean = render(meshOnFloor(smoothSphere()), m.integrator, m.accel);
  const Render withBad = render(meshOnFloor(bad), m.integrator, m.accel);
  EXPECT_EQ(nonFinitePixels(withBad.film), 0u);
  EXPECT_EQ(withBad.stats.rays.nanSamples, 0u);
  // The same rays hit the same triangles: the images agree exactly.
  EXPECT_EQ(differingPixels(withBad.film, clean.film, 0.0f), 0u);
}

TEST_P(CodeBuiltMesh, NanNormalsFallBackToTheGeometricNormal) {
  const Method m = GetParam();
  TriangleMesh poisoned = smoothSphere();
  const size_t bad = poisonNormals(poisoned);
  ASSERT_GT(bad, 20u);
  const Render clean = render(meshOnFloor(smoothSphere()), m.integrator, m.accel);
  const Render r = render(meshOnFloor(poisoned), m.integrator, m.accel);
  EXPECT_EQ(nonFinitePixels(r.film), 0u);
  EXPECT_EQ(r.stats.rays.nanSamples, 0u);
  // Triangles touching a bad vertex are shaded flat: facets, not holes or black pixels.
  const size_t differing = differingPixels(r.film, clean.film, 0.1f);
  std::printf("%s/%s: %zu NaN normals, %zu of %d pixels differ by > 0.1 from smooth shading\n",
              m.integrator, m.accel, bad, differing, kW * kH);
  EXPECT_LT(differing, size_t(kW * kH / 20));
}

INSTANTIATE_TEST_SUITE_P(Methods, CodeBuiltMesh,
                         ::testing::Values(Method{"whitted", "embree"}, Method{"whitted", "bvh"},
                                           Method{"path", "embree"}, Method{"path", "bvh"}),
                         [](const auto& info) {
                           return std::string(info.param.integrator) + "_" + info.param.accel;
                         });

TEST(CodeBuiltMesh, WithoutTheFallbackNanNormalsPoisonPixels) {
  // What Scene::surface's fallback prevents: interpolating the normals as they are gives a NaN
  // shading normal wherever a triangle touches a bad vertex (NaN x 0 is NaN), visible pixels.
  TriangleMesh poisoned = smoothSphere();
  poisonNormals(poisoned);
  const SceneWithCamera a = meshOnFloor(poisoned);
  const Scene& s = a.scene;
  auto camera = Camera::create(a.camera, kW, kH);
  auto accel = makeAccelerator("embree", s);
  size_t nanNormals = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      Hit hit;
      if (!accel->intersect(camera->generateRay(x + 0.5f, y + 0.5f), hit)) continue;
      const Primitive& p = s.primitives[hit.primitive];
      if (p.kind != Primitive::Kind::kMesh || p.mesh != 0) continue;
      const TriangleMesh& m = s.meshes[p.mesh];
      const uint32_t* t = &m.indices[3 * hit.triangle];
      const Vec3 n = (1 - hit.b1 - hit.b2) * m.normals[t[0]] + hit.b1 * m.normals[t[1]] +
                     hit.b2 * m.normals[t[2]];
      nanNormals += isFinite(n) ? 0 : 1;
    }
  std::printf("naive interpolation: %zu of %d pixels get a NaN shading normal\n", nanNormals,
              kW * kH);
  EXPECT_GT(nanNormals, size_t(kW * kH / 20));
}

// --- The same mesh from a glTF file ----------------------------------------------------------

/// Writes the mesh (POSITION, NORMAL, uint32 indices) as scene.gltf + scene.bin in a fresh
/// folder, with a sky (TRAY_environment) and returns the .gltf path.
std::string writeGltf(const TriangleMesh& m) {
  static_assert(sizeof(Vec3) == 12, "positions and normals are written as packed float3");
  static int counter = 0;
  const fs::path dir = test::testDir() / ("mesh" + std::to_string(counter++));
  fs::create_directories(dir);
  std::ofstream bin(dir / "scene.bin", std::ios::binary);
  auto bytes = [&](const void* p, size_t n) {
    bin.write(static_cast<const char*>(p), std::streamsize(n));
  };
  const size_t posBytes = m.positions.size() * sizeof(Vec3), idxBytes = m.indices.size() * 4;
  bytes(m.positions.data(), posBytes);
  bytes(m.normals.data(), posBytes);
  bytes(m.indices.data(), idxBytes);
  bin.close();
  const Bounds3 b = m.bounds();
  std::ostringstream j;
  j << R"({"asset":{"version":"2.0"},"extensionsUsed":["TRAY_environment"],)"
    << R"("scene":0,"scenes":[{"nodes":[0],"extensions":{"TRAY_environment":{"background":[1,1,1],"ambient":[0.5,0.5,0.5]}}}],)"
    << R"("nodes":[{"mesh":0}],"meshes":[{"primitives":[{"attributes":{"POSITION":0,"NORMAL":1},"indices":2}]}],)"
    << R"("buffers":[{"uri":"scene.bin","byteLength":)" << posBytes * 2 + idxBytes << "}],"
    << R"("bufferViews":[{"buffer":0,"byteLength":)" << posBytes << R"(},{"buffer":0,"byteOffset":)"
    << posBytes << R"(,"byteLength":)" << posBytes << R"(},{"buffer":0,"byteOffset":)"
    << 2 * posBytes << R"(,"byteLength":)" << idxBytes << "}],"
    << R"("accessors":[{"bufferView":0,"componentType":5126,"type":"VEC3","count":)"
    << m.positions.size() << R"(,"min":[)" << b.lo.x << ',' << b.lo.y << ',' << b.lo.z
    << R"(],"max":[)" << b.hi.x << ',' << b.hi.y << ',' << b.hi.z << "]},"
    << R"({"bufferView":1,"componentType":5126,"type":"VEC3","count":)" << m.positions.size()
    << "},"
    << R"({"bufferView":2,"componentType":5125,"type":"SCALAR","count":)" << m.indices.size()
    << "}]}";
  std::ofstream(dir / "scene.gltf") << j.str();
  return (dir / "scene.gltf").string();
}

TriangleMesh badSphere(size_t* poisoned) {
  TriangleMesh m = smoothSphere();
  *poisoned = poisonNormals(m);
  addBadTriangles(m);
  return m;
}

TEST(GltfMesh, LoaderDropsBadTrianglesAndCountsThemInOneWarningEach) {
  size_t poisoned = 0;
  const TriangleMesh m = badSphere(&poisoned);
  LoadReport report;
  SceneWithCamera loaded{loadGltf(writeGltf(m), {}, &report),
                         lookAt({0, 0.5f, 4}, {0, 0, 0}, 0.8f)};
  const Scene& s = loaded.scene;
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].triangleCount(), smoothSphere().triangleCount());
  ASSERT_EQ(report.warnings.size(), 2u);
  EXPECT_NE(report.warnings[0].find("dropped " + std::to_string(kBadTriangles) + " degenerate"),
            std::string::npos)
      << report.warnings[0];
  EXPECT_NE(report.warnings[1].find("replaced " + std::to_string(poisoned) + " non-finite"),
            std::string::npos)
      << report.warnings[1];
  for (const char* integrator : {"whitted", "path"}) {
    const Render r = render(loaded, integrator, "embree");
    EXPECT_EQ(nonFinitePixels(r.film), 0u) << integrator;
    EXPECT_EQ(r.stats.rays.nanSamples, 0u) << integrator;
  }
}

TEST(GltfMesh, TrayRenderPrintsOneLinePerKindAndNoNanPixels) {
  size_t poisoned = 0;
  const std::string scene = writeGltf(badSphere(&poisoned));
  const fs::path dir = fs::path(scene).parent_path();
  const std::string cmd = std::string(TRAY_RENDER_BIN) + " " + scene + " -o " +
                          (dir / "out.exr").string() +
                          " --integrator path --spp 4 --resolution 64x48 --float -q 2> " +
                          (dir / "stderr.txt").string();
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  std::ifstream err(dir / "stderr.txt");
  std::vector<std::string> warnings;
  for (std::string line; std::getline(err, line);)
    if (line.rfind("warning:", 0) == 0) warnings.push_back(line);
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_NE(
      warnings[0].find("dropped " + std::to_string(kBadTriangles) + " degenerate triangle(s)"),
      std::string::npos)
      << warnings[0];
  EXPECT_NE(warnings[1].find("replaced " + std::to_string(poisoned) + " non-finite normal(s)"),
            std::string::npos)
      << warnings[1];
  // Read back: every value finite.
  auto in = OIIO::ImageInput::open((dir / "out.exr").string());
  ASSERT_TRUE(in);
  std::vector<float> px(size_t(in->spec().image_pixels()) * size_t(in->spec().nchannels));
  ASSERT_TRUE(in->read_image(0, 0, 0, in->spec().nchannels, OIIO::TypeDesc::FLOAT, px.data()));
  ASSERT_EQ(px.size(), size_t(kW * kH * in->spec().nchannels));
  EXPECT_EQ(std::count_if(px.begin(), px.end(), [](float v) { return !std::isfinite(v); }), 0);
}

}  // namespace
}  // namespace tray
