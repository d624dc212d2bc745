// Animation sampling (glTF 2.0 §3.11, Appendix C) against closed forms, and the loader at a
// time: node transforms, morph targets (§3.7.2.2) and skins (§3.7.3) on tiny generated files
// and on the Khronos samples in ../shared/gltf-features. Expected skinned bounds come from a
// separate Python reading (json + struct, doubles, no TRay code): joint world x inverse bind
// matrices blended per vertex.
#include "gltf/gltf_animation.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>

#include "core/error.h"
#include "gltf/gltf_loader.h"
#include "tests/base64.h"
#include "tests/error_of.h"
#include "tests/temp_dir.h"

namespace tray {
namespace {

namespace fs = std::filesystem;
const fs::path kFeatures = fs::path(TRAY_SHARED_DIR) / "gltf-features";

// ---------------------------------------------------------------------------------------------
// Keyframes.

Keyframes keys(std::vector<float> times, std::vector<float> values, int width, Interpolation mode,
               bool quaternion = false) {
  Keyframes k;
  k.times = std::move(times), k.values = std::move(values), k.width = width, k.mode = mode;
  k.quaternion = quaternion;
  return k;
}

TEST(Keyframes, LinearIsTheMidpointAndClampsAtBothEnds) {
  Keyframes k = keys({1, 3}, {0, 0, 0, 2, 4, 6}, 3, Interpolation::kLinear);
  EXPECT_EQ(sampleKeyframes(k, 2), (std::vector<float>{1, 2, 3}));
  EXPECT_EQ(sampleKeyframes(k, 1.5f), (std::vector<float>{0.5f, 1, 1.5f}));
  EXPECT_EQ(sampleKeyframes(k, -5), (std::vector<float>{0, 0, 0}));  // before the first key
  EXPECT_EQ(sampleKeyframes(k, 9), (std::vector<float>{2, 4, 6}));   // after the last
}

TEST(Keyframes, StepHoldsEachValueUntilTheNextKey) {
  Keyframes k = keys({0, 1, 2}, {10, 20, 30}, 1, Interpolation::kStep);
  EXPECT_EQ(sampleKeyframes(k, 0.999f)[0], 10);
  EXPECT_EQ(sampleKeyframes(k, 1)[0], 20);
  EXPECT_EQ(sampleKeyframes(k, 1.7f)[0], 20);
  EXPECT_EQ(sampleKeyframes(k, 2)[0], 30);
  EXPECT_EQ(sampleKeyframes(k, 7)[0], 30);
}

TEST(Keyframes, CubicSplineFollowsHermiteWithScaledTangents) {
  // (in, value, out) per key. Values 0 and 2 over [0, 2] with slope 1 at both ends: the Hermite
  // curve is the line p(t) = t, which only holds if tangents are scaled by the interval (2).
  Keyframes line = keys({0, 2}, {9, 0, 1, 1, 2, 9}, 1, Interpolation::kCubicSpline);
  for (float t : {0.25f, 0.5f, 1.0f, 1.3f}) EXPECT_NEAR(sampleKeyframes(line, t)[0], t, 1e-6);
  EXPECT_EQ(sampleKeyframes(line, 2)[0], 2);  // the last value, not a tangent
  // v0 = 0, b0 = 1, v1 = 1, a1 = 3, td = 2 at u = 1/2: h00 = h01 = 1/2, h10 = 1/8, h11 = -1/8:
  // 0 + 2/8 + 1/2 - 6/8 = 0.
  Keyframes k = keys({0, 2}, {0, 0, 1, 3, 1, 0}, 1, Interpolation::kCubicSpline);
  EXPECT_NEAR(sampleKeyframes(k, 1)[0], 0, 1e-6);
  // u = 1/4: h00 = 27/32, h10 = 9/64, h01 = 5/32, h11 = -3/64: 18/64 + 5/32 - 18/64 = 5/32.
  EXPECT_NEAR(sampleKeyframes(k, 0.5f)[0], 5.0 / 32, 1e-6);
}

TEST(Keyframes, SlerpHalfwayThrough90DegreesIs45OnTheShortPath) {
  const float s = std::sqrt(0.5f);
  const std::vector<float> half{0, 0, float(std::sin(M_PI / 8)), float(std::cos(M_PI / 8))};
  Keyframes k = keys({0, 1}, {0, 0, 0, 1, 0, 0, s, s}, 4, Interpolation::kLinear, true);
  std::vector<float> q = sampleKeyframes(k, 0.5f);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(q[size_t(i)], half[size_t(i)], 1e-6);
  // The same rotation stored negated: still 45 degrees, not the long way round (315).
  Keyframes neg = keys({0, 1}, {0, 0, 0, 1, 0, 0, -s, -s}, 4, Interpolation::kLinear, true);
  q = sampleKeyframes(neg, 0.5f);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(q[size_t(i)], half[size_t(i)], 1e-6);
  // A quarter of the way: 22.5 degrees (angle linear in time).
  q = sampleKeyframes(k, 0.25f);
  EXPECT_NEAR(q[2], std::sin(M_PI / 16), 1e-6);
}

TEST(Keyframes, CubicRotationsAreNormalised) {
  Keyframes k =
      keys({0, 1}, {0, 0, 0, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0}, 4,
           Interpolation::kCubicSpline, true);
  std::vector<float> q = sampleKeyframes(k, 0.5f);
  EXPECT_NEAR(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3], 1, 1e-6);
}

// ---------------------------------------------------------------------------------------------
// Tiny documents: one base64 buffer, written into a fresh temporary folder.

class Doc {
 public:
  template <typename T>
  int add(const std::vector<T>& v, int componentType, const char* type, int components,
          bool normalized = false) {
    while (bytes_.size() % 4) bytes_ += '\0';
    const size_t offset = bytes_.size();
    bytes_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
    views_ += sep(views_) + "{\"buffer\":0,\"byteOffset\":" + std::to_string(offset) +
              ",\"byteLength\":" + std::to_string(v.size() * sizeof(T)) + "}";
    accessors_ += sep(accessors_) + "{\"bufferView\":" + std::to_string(count_) +
                  ",\"componentType\":" + std::to_string(componentType) + ",\"type\":\"" + type +
                  "\",\"count\":" + std::to_string(v.size() / size_t(components)) +
                  (normalized ? ",\"normalized\":true" : "") + "}";
    return count_++;
  }
  int floats(const std::vector<float>& v, const char* type, int n) { return add(v, 5126, type, n); }
  Scene load(const std::string& rest, const LoadOptions& options = {},
             LoadReport* report = nullptr) const {
    static std::atomic<int> counter{0};
    const fs::path dir = test::testDir() / ("doc" + std::to_string(counter++));
    fs::create_directories(dir);
    const fs::path file = dir / "scene.gltf";
    std::ofstream(file) << "{\"asset\":{\"version\":\"2.0\"},\"buffers\":[{\"byteLength\":"
                        << bytes_.size() << ",\"uri\":\"data:application/octet-stream;base64,"
                        << test::base64(bytes_) << "\"}],\"bufferViews\":[" << views_
                        << "],\"accessors\":[" << accessors_ << "]," << rest << "}";
    return loadGltf(file.string(), options, report);
  }

 private:
  static std::string sep(const std::string& s) { return s.empty() ? "" : ","; }
  std::string bytes_, views_, accessors_;
  int count_ = 0;
};

LoadOptions at(float t) {
  LoadOptions o;
  o.time = t;
  return o;
}

/// A triangle (accessor 0) as mesh 0; accessors 1 and 2 hold times {0, 1} and translations
/// (0,0,0) -> (2,0,0).
Doc translatedTriangle() {
  Doc d;
  d.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
  d.floats({0, 1}, "SCALAR", 1);
  d.floats({0, 0, 0, 2, 0, 0}, "VEC3", 3);
  return d;
}
const std::string kTranslated =
    R"("scenes":[{"nodes":[0]}],"nodes":[{"mesh":0,"translation":[0,0,5]}],
       "meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],
       "animations":[{"channels":[{"sampler":0,"target":{"node":0,"path":"translation"}}],
                      "samplers":[{"input":1,"output":2}]}])";

TEST(GltfAnimation, TimeReplacesTheNodeTranslationAndNoTimeKeepsIt) {
  Doc d = translatedTriangle();
  Scene still = d.load(kTranslated);
  EXPECT_EQ(still.primitives.at(0).toWorld.point({0, 0, 0}).z, 5.0f);
  Scene moved = d.load(kTranslated, at(0.25f));
  const Vec3 o = moved.primitives.at(0).toWorld.point({0, 0, 0});
  EXPECT_FLOAT_EQ(o.x, 0.5f);
  EXPECT_EQ(o.z, 0.0f);  // animated translation replaces the node's, all three components
}

TEST(GltfAnimation, InvalidSamplersNameTheAccessor) {
  Doc d;
  d.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
  d.floats({0, 1, 1}, "SCALAR", 1);                  // 1: times not strictly increasing
  d.floats({0, 0, 0, 1, 0, 0, 2, 0, 0}, "VEC3", 3);  // 2: three translations
  d.floats({0, 1, 2}, "SCALAR", 1);                  // 3: good times
  d.floats({0, 0, 0, 1, 0, 0}, "VEC3", 3);           // 4: two translations only
  auto doc = [](int input, int output, const char* interpolation) {
    return std::string(
               R"("nodes":[{"mesh":0}],"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],
       "animations":[{"channels":[{"sampler":0,"target":{"node":0,"path":"translation"}}],
                      "samplers":[{"input":)") +
           std::to_string(input) + ",\"output\":" + std::to_string(output) +
           ",\"interpolation\":\"" + interpolation + "\"}]}]";
  };
  EXPECT_NE(errorOf([&] {
              d.load(doc(1, 2, "LINEAR"));
            }).find("accessor 1 (animation input) is not strictly increasing at keyframe 2"),
            std::string::npos);
  EXPECT_NE(errorOf([&] {
              d.load(doc(3, 4, "LINEAR"));
            }).find("accessor 4 (animation output) has 2 elements, expected 3"),
            std::string::npos);
  // CUBICSPLINE needs in-tangent, value and out-tangent per key: 9 for 3 keys.
  EXPECT_NE(errorOf([&] { d.load(doc(3, 2, "CUBICSPLINE")); }).find("expected 9"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { d.load(doc(3, 2, "SMOOTH")); }).find("unknown interpolation 'SMOOTH'"),
            std::string::npos);
  EXPECT_EQ(errorOf([&] { d.load(doc(3, 2, "STEP"), at(1)); }), "(no error)");
}

TEST(GltfAnimation, AnimationIsChosenByIndexOrName) {
  Doc d = translatedTriangle();
  d.floats({1, 1, 1, 3, 3, 3}, "VEC3", 3);  // 3: scales
  const std::string two =
      kTranslated.substr(0, kTranslated.size() - 1) +
      R"(,{"name":"grow","channels":[{"sampler":0,"target":{"node":0,"path":"scale"}}],
                      "samplers":[{"input":1,"output":3}]}])";
  LoadOptions o = at(1);
  auto corner = [&] { return d.load(two, o).primitives.at(0).toWorld.point({1, 0, 0}); };
  EXPECT_FLOAT_EQ(corner().x, 3.0f);  // by default the first only: translated by 2, unscaled
  o.animation = "all";
  const Vec3 all = corner();  // both: translated to (2, 0, 0) and scaled by 3
  EXPECT_FLOAT_EQ(all.x, 5.0f);
  EXPECT_FLOAT_EQ(all.z, 0.0f);
  o.animation = "grow";  // only the scale: the node keeps its translation (0, 0, 5)
  const Vec3 grow = corner();
  EXPECT_FLOAT_EQ(grow.x, 3.0f);
  EXPECT_FLOAT_EQ(grow.z, 5.0f);
  o.animation = "0";
  EXPECT_FLOAT_EQ(corner().x, 3.0f);  // translated by 2, unscaled
  o.animation = "walk";
  EXPECT_NE(errorOf([&] { d.load(two, o); })
                .find("--animation walk: no such animation (the file has 2: 0, 1 'grow'; or "
                      "first, all)"),
            std::string::npos);
}

/// A triangle with one morph target moving vertex 2 by (0, 0, 1).
Doc morphedTriangle() {
  Doc d;
  d.floats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3);
  d.floats({0, 0, 0, 0, 0, 0, 0, 0, 1}, "VEC3", 3);
  return d;
}

TEST(GltfMorph, NodesWithDifferentWeightsGetTheirOwnGeometry) {
  Scene s = morphedTriangle().load(
      R"("scenes":[{"nodes":[0,1,2,3]}],
         "nodes":[{"mesh":0},{"mesh":0,"weights":[1]},{"mesh":0,"weights":[0]},{"mesh":0}],
         "meshes":[{"primitives":[{"attributes":{"POSITION":0},"targets":[{"POSITION":1}]}],
                    "weights":[0.5]}])");
  ASSERT_EQ(s.primitives.size(), 4u);
  auto z = [&](int node) {
    for (const auto& p : s.primitives)
      if (p.objectId == node) return s.meshes[p.mesh].positions[2].z;
    return -1.0f;
  };
  EXPECT_EQ(z(0), 0.5f);  // mesh.weights
  EXPECT_EQ(z(1), 1.0f);  // node.weights override them
  EXPECT_EQ(z(2), 0.0f);  // all zero: the shared, unmorphed mesh
  EXPECT_EQ(z(3), 0.5f);
  EXPECT_EQ(s.meshes.size(), 4u);  // three morphed copies and the shared mesh
}

TEST(GltfMorph, WrongWeightCountIsAnError) {
  EXPECT_NE(errorOf([] {
              morphedTriangle().load(
                  R"("nodes":[{"mesh":0,"weights":[1,2]}],
                     "meshes":[{"primitives":[{"attributes":{"POSITION":0},"targets":[{"POSITION":1}]}]}])");
            }).find("has 2 morph weights for 1 targets"),
            std::string::npos);
}

/// Two joints: node 1 at the origin, node 2 at (0, 0, 1) under it, rotated by `rotation`.
/// The triangle's vertex 2 follows joint 1 only; WEIGHTS as normalized unsigned bytes.
std::string skinDoc(const std::string& rotation, int weightsAccessor) {
  return R"("scenes":[{"nodes":[0,1]}],
     "nodes":[{"mesh":0,"skin":0,"translation":[100,0,0]},{"children":[2]},
              {"translation":[0,0,1],"rotation":)" +
         rotation + R"(}],
     "skins":[{"joints":[1,2],"inverseBindMatrices":3}],
     "meshes":[{"primitives":[{"attributes":{"POSITION":0,"JOINTS_0":1,"WEIGHTS_0":)" +
         std::to_string(weightsAccessor) + "}}]}]";
}
Doc skinnedTriangle() {
  Doc d;
  d.floats({0, 0, 0, 1, 0, 0, 0, 1, 1}, "VEC3", 3);
  d.add(std::vector<uint8_t>{0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0}, 5121, "VEC4", 4);
  d.add(std::vector<uint8_t>{255, 0, 0, 0, 255, 0, 0, 0, 255, 0, 0, 0}, 5121, "VEC4", 4, true);
  // Inverse bind matrices: identity, and translate(0, 0, -1) for joint 1 (column major).
  d.floats({1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0,  1,
            1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -1, 1},
           "MAT4", 16);
  d.add(std::vector<uint8_t>{255, 0, 0, 0, 255, 0, 0, 0, 200, 0, 0, 0}, 5121, "VEC4", 4, true);
  return d;
}

TEST(GltfSkin, JointsPlaceTheMeshAndTheNodeTransformIsIgnored) {
  // Rotation 90 degrees about x: joint 1 maps (0, 1, 1) -> (0,0,1) + Rx(0, 1, 0) = (0, 0, 2).
  const float s = std::sqrt(0.5f);
  const std::string rx = "[" + std::to_string(s) + ",0,0," + std::to_string(s) + "]";
  LoadReport report;
  Scene scene = skinnedTriangle().load(skinDoc(rx, 2), {}, &report);
  ASSERT_EQ(scene.primitives.size(), 1u);
  const Primitive& p = scene.primitives[0];
  const Vec3 v = p.toWorld.point(scene.meshes[p.mesh].positions[2]);
  EXPECT_NEAR(v.x, 0, 1e-5);  // not 100: the skinned node's translation is ignored
  EXPECT_NEAR(v.y, 0, 1e-5);
  EXPECT_NEAR(v.z, 2, 1e-5);
  EXPECT_TRUE(report.warnings.empty());
}

TEST(GltfSkin, WeightsOffByMoreThanTheToleranceAreRescaledWithOneWarning) {
  LoadReport report;
  Scene scene = skinnedTriangle().load(skinDoc("[0,0,0,1]", 4), {}, &report);
  const Primitive& p = scene.primitives.at(0);
  // 200/255 renormalised to 1 on joint 1 at rest: the vertex stays where it is.
  EXPECT_NEAR(p.toWorld.point(scene.meshes[p.mesh].positions[2]).z, 1, 1e-6);
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_NE(report.warnings[0].find("1 skinned vertex(es) with weights not summing to 1"),
            std::string::npos);
}

TEST(GltfSkin, JointOutOfRangeIsAnError) {
  Doc d = skinnedTriangle();
  d.add(std::vector<uint8_t>{0, 0, 0, 0, 0, 0, 0, 0, 7, 0, 0, 0}, 5121, "VEC4", 4);  // 5
  std::string doc = skinDoc("[0,0,0,1]", 2);
  doc.replace(doc.find("\"JOINTS_0\":1"), 12, "\"JOINTS_0\":5");
  EXPECT_NE(errorOf([&] {
              d.load(doc);
            }).find("accessor 5 (JOINTS_0) joint 7 at vertex 2 is out of range"),
            std::string::npos);
}

// Issue 40: a skin's `skeleton` naming a node that does not exist was accepted silently.
TEST(GltfSkin, SkeletonNodeOutOfRangeIsAnError) {
  std::string doc = skinDoc("[0,0,0,1]", 2);
  const std::string joints = R"("joints":[1,2])";
  doc.replace(doc.find(joints), joints.size(), joints + R"(,"skeleton":9)");
  EXPECT_NE(errorOf([&] { skinnedTriangle().load(doc); })
                .find("skin 0 names skeleton node 9, which does not exist"),
            std::string::npos);
  doc.replace(doc.find(R"("skeleton":9)"), 12, R"("skeleton":1)");  // a real node is fine
  EXPECT_EQ(errorOf([&] { skinnedTriangle().load(doc); }), "(no error)");
}

// ---------------------------------------------------------------------------------------------
// Khronos samples.

Bounds3 worldBounds(const Scene& s) {
  Bounds3 b;
  for (const auto& p : s.primitives)
    for (const Vec3& v : s.meshes[p.mesh].positions) b.extend(p.toWorld.point(v));
  return b;
}

void expectBounds(const Scene& s, Vec3 lo, Vec3 hi, float tolerance) {
  const Bounds3 b = worldBounds(s);
  EXPECT_NEAR(b.lo.x, lo.x, tolerance);
  EXPECT_NEAR(b.lo.y, lo.y, tolerance);
  EXPECT_NEAR(b.lo.z, lo.z, tolerance);
  EXPECT_NEAR(b.hi.x, hi.x, tolerance);
  EXPECT_NEAR(b.hi.y, hi.y, tolerance);
  EXPECT_NEAR(b.hi.z, hi.z, tolerance);
}

TEST(GltfSamplesAnimated, SimpleSkinBendsAtItsJoint) {
  const std::string file = (kFeatures / "SimpleSkin.gltf").string();
  // At rest: the 1 x 2 strip, x in [-0.5, 0.5], y in [0, 2].
  expectBounds(loadGltf(file), {-0.5f, 0, 0}, {0.5f, 2, 0}, 1e-6f);
  // t = 1: joint 2 (at y = 1) turned 90 degrees about z. By hand: the top row (weight 1 on
  // joint 2) goes to (-1, 0.5) and (-1, 1.5); rows at y = 0.5 / 1 / 1.5 blend 3:1, 1:1, 1:3 and
  // reach x = 0.5 at most (the fixed bottom row) and y = 1.5 at most.
  expectBounds(loadGltf(file, at(1)), {-1, 0, 0}, {0.5f, 1.5f, 0}, 1e-5f);
  // t = 0.5: 45 degrees (key 1, q = (0, 0, 0.383, 0.924)); the Python reading.
  expectBounds(loadGltf(file, at(0.5f)), {-1.0608342f, 0, 0}, {0.5517767f, 2.0604859f, 0}, 1e-4f);
}

TEST(GltfSamplesAnimated, RiggedSimpleBoundsMatchAnIndependentReading) {
  const std::string file = (kFeatures / "RiggedSimple.glb").string();
  expectBounds(loadGltf(file, at(0.5f)), {-1, -4.5750771f, -1}, {1.6731896f, 4.5335192f, 1}, 1e-4f);
  expectBounds(loadGltf(file, at(1)), {-1, -4.5750771f, -1}, {2.8664947f, 4.1005095f, 1}, 1e-4f);
}

TEST(GltfSamplesAnimated, WalkingFiguresMatchAnIndependentReading) {
  // 19 joints each; CesiumMan mid-stride: its feet 0.97 apart along z (the walking direction).
  expectBounds(loadGltf((kFeatures / "CesiumMan.glb").string(), at(1)),
               {-0.2021819f, -0.0014262f, -0.5075166f}, {0.1668429f, 1.4572350f, 0.4623297f},
               1e-4f);
  expectBounds(loadGltf((kFeatures / "RiggedFigure.glb").string(), at(0.5f)),
               {-0.4232015f, 0, -0.1208366f}, {0.4127010f, 1.4695586f, 0.2220496f}, 1e-4f);
}

TEST(GltfSamplesAnimated, SimpleMorphVerticesAtTheirWeights) {
  const std::string file = (kFeatures / "SimpleMorph.gltf").string();
  // Vertex 2 = (0.5, 0.5) + w0 (-1, 1) + w1 (1, 1); mesh.weights (0.5, 0.5) without a time.
  const Vec3 still = loadGltf(file).meshes.at(0).positions.at(2);
  EXPECT_EQ(still.x, 0.5f);
  EXPECT_EQ(still.y, 1.5f);
  // t = 1.5: halfway between keys (0, 1) and (1, 1): weights (0.5, 1).
  const Vec3 v = loadGltf(file, at(1.5f)).meshes.at(0).positions.at(2);
  EXPECT_FLOAT_EQ(v.x, 1.0f);
  EXPECT_FLOAT_EQ(v.y, 2.0f);
}

TEST(GltfSamplesAnimated, AnimatedMorphCubeVertexAtAKeyframe) {
  const std::string file = (kFeatures / "AnimatedMorphCube.glb").string();
  // Key 102 (t = 3.399998188): weights (3.8147e-8, 1). Vertex 5: y = -0.0100000054
  // + 3.8147e-8 * 0.0189325 + 0.0198908355 (targets' POSITION displacements).
  Scene s = loadGltf(file, at(3.399998188018799f));
  EXPECT_NEAR(s.meshes.at(0).positions.at(5).y, 0.0098908308, 1e-7);
  EXPECT_NEAR(loadGltf(file).meshes.at(0).positions.at(5).y, -0.0100000054, 1e-9);
}

TEST(GltfSamplesAnimated, BoxAnimatedAndAnimatedCubeTransforms) {
  // BoxAnimated: node 0 rises to y = 2.52 by t = 1.25; node 2 turns from identity to 180
  // degrees about x over [1.25, 2.5]: at 1.875, 90 degrees, so its +y maps to +z.
  Scene box = loadGltf((kFeatures / "BoxAnimated.glb").string(), at(1.875f));
  for (const auto& p : box.primitives) {
    if (p.objectId != 2) continue;
    const Vec3 v = p.toWorld.point({0, 1, 0});
    EXPECT_NEAR(v.x, 0, 1e-5);
    EXPECT_NEAR(v.y, 2.52f, 1e-5);
    EXPECT_NEAR(std::fabs(v.z), 1, 1e-5);
  }
  // AnimatedCube: identity at t = 0 to 180 degrees about y at t = 1, stored as (0, 1, 0,
  // -4.4e-8): the dot product with the first key is -4.4e-8 < 0, so the shortest-path rule
  // negates it and the cube turns by -90 degrees at t = 0.5: +x to +z. Without a time, the
  // node's own rotation (180 degrees about y): +x to -x.
  const std::string cube = (kFeatures / "AnimatedCube/AnimatedCube.gltf").string();
  const Vec3 x = loadGltf(cube, at(0.5f)).primitives.at(0).toWorld.vector({1, 0, 0});
  EXPECT_NEAR(x.x, 0, 1e-6);
  EXPECT_NEAR(x.z, 1, 1e-6);
  EXPECT_NEAR(loadGltf(cube).primitives.at(0).toWorld.vector({1, 0, 0}).x, -1, 1e-6);
}

}  // namespace
}  // namespace tray

namespace tray {
namespace {

TEST(GltfDocument, ParsedOnceConvertsEachTimeAsLoadGltfDoes) {
  // --frames parses the file once and converts a scene per frame: every frame must be the
  // scene loadGltf makes at that time, vertex for vertex.
  const std::string file = (fs::path(TRAY_SHARED_DIR) / "gltf-features" / "CesiumMan.glb").string();
  LoadOptions parseOptions;
  const GltfDocument document(file, parseOptions);
  for (float t : {0.0f, 0.7f, 1.3f}) {
    LoadOptions o;
    o.time = t;
    const Scene once = document.scene(o), again = loadGltf(file, o);
    ASSERT_EQ(once.meshes.size(), again.meshes.size());
    for (size_t m = 0; m < once.meshes.size(); ++m) {
      ASSERT_EQ(once.meshes[m].positions.size(), again.meshes[m].positions.size());
      for (size_t v = 0; v < once.meshes[m].positions.size(); ++v) {
        EXPECT_EQ(once.meshes[m].positions[v].x, again.meshes[m].positions[v].x);
        EXPECT_EQ(once.meshes[m].positions[v].y, again.meshes[m].positions[v].y);
        EXPECT_EQ(once.meshes[m].positions[v].z, again.meshes[m].positions[v].z);
      }
    }
  }
  // And the document's frames differ from each other (the figure walks).
  LoadOptions a, b;
  a.time = 0.2f, b.time = 0.9f;
  EXPECT_NE(document.scene(a).bounds().diagonal().x, document.scene(b).bounds().diagonal().x);
}

}  // namespace
}  // namespace tray
