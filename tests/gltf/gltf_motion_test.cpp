// Motion steps from glTF animations (gltf/gltf_motion.cpp): each step of a moving node is its
// world transform at that step's time, vertex for vertex what --time alone gives; nodes that
// do not move over the shutter stay static.
#include "gltf/gltf_motion.h"

#include <gtest/gtest.h>

#include "core/motion.h"
#include "gltf/gltf_loader.h"

namespace tray {
namespace {

const std::string kBox = std::string(TRAY_SHARED_DIR) + "/gltf-features/BoxAnimated.glb";

LoadOptions at(float time) {
  LoadOptions o;
  o.time = time;
  return o;
}

TEST(GltfMotion, EachStepIsTheWorldTransformAtItsTime) {
  LoadOptions o = at(1.0f);
  o.shutterOpen = 0.5f, o.shutterClose = 1.5f, o.motionSteps = 3;
  const Scene blurred = loadGltf(kBox, o);
  const Scene frame = loadGltf(kBox, at(1.0f));
  ASSERT_EQ(blurred.primitives.size(), frame.primitives.size());
  EXPECT_EQ(blurred.shutterOpen, 0.5f);
  EXPECT_EQ(blurred.shutterClose, 1.5f);
  const float times[3] = {0.5f, 1.0f, 1.5f};
  int moving = 0, still = 0;
  for (size_t i = 0; i < blurred.primitives.size(); ++i) {
    const Primitive& p = blurred.primitives[i];
    // The frame's own placement is kept for lights and framing.
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c)
        EXPECT_EQ(p.toWorld.m.m[r][c], frame.primitives[i].toWorld.m.m[r][c]);
    if (p.motion.empty()) {
      ++still;
      continue;
    }
    ++moving;
    ASSERT_EQ(p.motion.size(), 3u);
    for (int k = 0; k < 3; ++k) {
      const Scene posed = loadGltf(kBox, at(times[k]));
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c)
          EXPECT_FLOAT_EQ(p.motion[size_t(k)].m[r][c], posed.primitives[i].toWorld.m.m[r][c])
              << "primitive " << i << " step " << k;
    }
  }
  EXPECT_GT(moving, 0);  // the animated box
  EXPECT_GT(still, 0);   // the static base
  EXPECT_TRUE(blurred.moving());
}

// Skinned (SimpleSkin) and morphed (AnimatedMorphCube) vertices: each step's positions are
// the mesh's vertices as --time alone poses them at that step's time.
TEST(GltfMotion, DeformingVerticesAtEachStepAreThePoseAtItsTime) {
  for (const char* file : {"SimpleSkin.gltf", "AnimatedMorphCube.glb"}) {
    const std::string path = std::string(TRAY_SHARED_DIR) + "/gltf-features/" + file;
    LoadOptions o = at(1.0f);
    o.shutterOpen = 0.75f, o.shutterClose = 1.25f, o.motionSteps = 3;
    const Scene blurred = loadGltf(path, o);
    const float times[3] = {0.75f, 1.0f, 1.25f};
    int deforming = 0;
    for (size_t m = 0; m < blurred.meshes.size(); ++m) {
      const TriangleMesh& mesh = blurred.meshes[m];
      if (mesh.positionSteps.empty()) continue;
      ++deforming;
      ASSERT_EQ(mesh.positionSteps.size(), 3u);
      for (int k = 0; k < 3; ++k) {
        const Scene posed = loadGltf(path, at(times[k]));
        ASSERT_LT(m, posed.meshes.size());
        ASSERT_EQ(posed.meshes[m].positions.size(), mesh.positionSteps[size_t(k)].size());
        for (size_t v = 0; v < mesh.positions.size(); ++v)
          for (int a = 0; a < 3; ++a)
            EXPECT_EQ(mesh.positionSteps[size_t(k)][v][a], posed.meshes[m].positions[v][a])
                << file << " step " << k << " vertex " << v;
      }
    }
    EXPECT_GT(deforming, 0) << file;
    EXPECT_TRUE(blurred.moving()) << file;
  }
}

TEST(GltfMotion, PreviousFrameIsThePoseOneFrameBefore) {
  LoadOptions o = at(1.0f);
  o.previousTime = 1.0f - 1.0f / 24;
  const Scene scene = loadGltf(kBox, o);
  const Scene before = loadGltf(kBox, at(1.0f - 1.0f / 24));
  ASSERT_EQ(scene.previousToWorld.size(), scene.primitives.size());
  int moved = 0;
  for (size_t i = 0; i < scene.primitives.size(); ++i) {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c)
        EXPECT_FLOAT_EQ(scene.previousToWorld[i].m[r][c], before.primitives[i].toWorld.m.m[r][c]);
    moved += stepsMove({scene.previousToWorld[i], scene.primitives[i].toWorld.m});
  }
  EXPECT_GT(moved, 0);
  EXPECT_FALSE(scene.moving());                                   // no shutter: nothing blurs
  EXPECT_TRUE(loadGltf(kBox, at(1.0f)).previousToWorld.empty());  // not asked: not posed
}

TEST(GltfMotion, NoShutterOrNoTimeMeansNoMotion) {
  EXPECT_FALSE(loadGltf(kBox, at(1.0f)).moving());
  LoadOptions o;  // static pose: nothing to blur
  o.shutterOpen = 0.5f, o.shutterClose = 1.5f, o.motionSteps = 3;
  EXPECT_FALSE(loadGltf(kBox, o).moving());
  // A shutter over which the animation holds still (past its last key) moves nothing.
  o = at(100.0f);
  o.shutterOpen = 99.0f, o.shutterClose = 101.0f, o.motionSteps = 2;
  EXPECT_FALSE(loadGltf(kBox, o).moving());
}

}  // namespace
}  // namespace tray
