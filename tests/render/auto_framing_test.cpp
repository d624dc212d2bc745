// The automatic camera of an animated file without cameras is framed once for the whole
// animation (issue 39): before, each frame of a --frames sequence framed its own bounds, so the
// camera jittered and zoomed as the figure walked.
#include "render/auto_framing.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "render/job_scene.h"

namespace tray {
namespace {

namespace fs = std::filesystem;

const std::string kWalker =
    (fs::path(TRAY_SHARED_DIR) / "gltf-features" / "CesiumMan.glb").string();

RenderJob jobAt(const std::string& path, const char* time) {
  RenderJob job;
  job.scene.path = path;
  job.scene.allowAnyPath = true;
  job.resolution = "32x24";
  job.outputs.paths.clear();
  if (time) job.settings.set("time", time);
  return job;
}

CameraDesc preparedCamera(const RenderJob& job) {
  int placed = -2;
  const PreparedScene prepared = prepareJobScene(job, {}, nullptr, placed);
  EXPECT_EQ(placed, -1);  // no placed camera: the automatic one
  return prepared.cameraDesc();
}

bool sameMatrix(const Mat4& a, const Mat4& b) {
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c)
      if (a.m[r][c] != b.m[r][c]) return false;
  return true;
}

TEST(AutoFraming, EveryTimeOfTheAnimationGetsOneCamera) {
  const CameraDesc first = preparedCamera(jobAt(kWalker, "0"));
  for (const char* t : {"0.5", "1.25", "1.9"})
    EXPECT_TRUE(sameMatrix(preparedCamera(jobAt(kWalker, t)).toWorld.m, first.toWorld.m)) << t;
}

TEST(AutoFraming, TheSweepHoldsThePosesItSamples) {
  const RenderJob job = jobAt(kWalker, nullptr);
  const GltfDocument document(kWalker, loadOptionsOf(job));
  const auto swept = sweptFramingBounds(job, document);
  ASSERT_TRUE(swept);
  const auto range = document.animationRange(loadOptionsOf(job));
  ASSERT_TRUE(range);
  EXPECT_LT(range->first, range->second);
  Bounds3 frames;  // the frames alone differ from one another: the walker moves
  for (int i = 0; i < kFramingPoses; ++i) {
    LoadOptions options = loadOptionsOf(job);
    options.time = range->first + (range->second - range->first) * float(i) / (kFramingPoses - 1);
    const Bounds3 b = document.scene(options).bounds();
    for (int a = 0; a < 3; ++a) {
      EXPECT_LE(swept->lo[a], b.lo[a]);
      EXPECT_GE(swept->hi[a], b.hi[a]);
    }
    if (i == 0)
      frames = b;
    else
      EXPECT_FALSE(b.lo == frames.lo && b.hi == frames.hi) << "pose " << i << " = pose 0";
  }
}

TEST(AutoFraming, NotForNamedOrPlacedCamerasOrStillFiles) {
  RenderJob named = jobAt(kWalker, nullptr);
  named.camera.assign(1, '0');  // not = "0": GCC 12 warns falsely (-Wrestrict, PR 105329)
  const GltfDocument walker(kWalker, loadOptionsOf(named));
  EXPECT_FALSE(sweptFramingBounds(named, walker));
  const std::string box = (fs::path(TRAY_SHARED_DIR) / "gltf-samples" / "Box.glb").string();
  const RenderJob still = jobAt(box, nullptr);
  EXPECT_FALSE(sweptFramingBounds(still, GltfDocument(box, loadOptionsOf(still))));
  // A file that places a camera keeps it, animated or not.
  const std::string animated =
      (fs::path(TRAY_SHARED_DIR) / "gltf-features" / "BoxAnimated.glb").string();
  const RenderJob boxAnimated = jobAt(animated, nullptr);
  const GltfDocument doc(animated, loadOptionsOf(boxAnimated));
  if (!doc.scene(loadOptionsOf(boxAnimated)).cameras.empty()) {
    EXPECT_FALSE(sweptFramingBounds(boxAnimated, doc));
  }
}

TEST(AutoFraming, TheStaticPoseIsFramedAsBefore) {
  // Without --time nothing is swept: the file's own pose, framed by its own bounds.
  const RenderJob job = jobAt(kWalker, nullptr);
  const Scene scene = loadGltf(kWalker, loadOptionsOf(job));
  const CameraDesc expected = Camera::framing(scene.bounds(), 4.0f / 3.0f);
  EXPECT_TRUE(sameMatrix(preparedCamera(job).toWorld.m, expected.toWorld.m));
}

}  // namespace
}  // namespace tray
