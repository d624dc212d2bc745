// --camera N means the file's cameras[N], whatever order the nodes place them in; names pick
// by node or camera name; anything else is one error line listing the scene's cameras.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "gltf/gltf_loader.h"
#include "render/render_setup.h"
#include "tests/temp_dir.h"

namespace tray {
namespace {

namespace fs = std::filesystem;

/// Three perspective cameras (yfov 0.5, 0.6, 0.7 tell them apart), placed by nodes in the
/// order cameras[2], cameras[0], cameras[1]; camera 1 is named, the others are not.
Scene loadJson(const std::string& json) {
  const fs::path file = test::testDir() / "cams.gltf";
  std::ofstream(file) << json;
  Scene s = loadGltf(file.string());
  s.sourcePath = "cams.gltf";
  return s;
}

Scene threeCameras() {
  return loadJson(R"({"asset":{"version":"2.0"},"scene":0,
    "scenes":[{"nodes":[0,1,2]}],
    "cameras":[{"type":"perspective","perspective":{"yfov":0.5,"znear":0.1}},
               {"type":"perspective","name":"Wide","perspective":{"yfov":0.6,"znear":0.1}},
               {"type":"perspective","perspective":{"yfov":0.7,"znear":0.1}}],
    "nodes":[{"name":"Third","camera":2},{"name":"First","camera":0,"translation":[0,0,3]},
             {"name":"Second","camera":1}]})");
}

std::string errorOf(const Scene& s, const std::string& which) {
  try {
    findCamera(s, which);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(GltfCameras, PlacedCamerasKeepTheirGltfIndexAndNode) {
  const Scene s = threeCameras();
  ASSERT_EQ(s.cameras.size(), 3u);
  EXPECT_EQ(s.cameras[0].gltfIndex, 2);
  EXPECT_EQ(s.cameras[0].nodeName, "Third");
  EXPECT_EQ(s.cameras[1].gltfIndex, 0);
  EXPECT_EQ(s.cameras[2].name, "Wide");
  EXPECT_EQ(s.cameras[2].nodeName, "Second");
}

TEST(GltfCameras, IndexMeansTheFilesCamerasArray) {
  const Scene s = threeCameras();
  EXPECT_FLOAT_EQ(chooseCamera(s, "0").yfov, 0.5f);
  EXPECT_FLOAT_EQ(chooseCamera(s, "1").yfov, 0.6f);
  EXPECT_FLOAT_EQ(chooseCamera(s, "2").yfov, 0.7f);
  EXPECT_FLOAT_EQ(chooseCamera(s, 2).yfov, 0.7f);
  // The default is cameras[0] (placed second here), so it equals --camera 0.
  EXPECT_EQ(findCamera(s, ""), 1);
  EXPECT_FLOAT_EQ(chooseCamera(s, -1).yfov, 0.5f);
}

TEST(GltfCameras, NamesPickByNodeOrCamera) {
  const Scene s = threeCameras();
  EXPECT_FLOAT_EQ(chooseCamera(s, "Third").yfov, 0.7f);
  EXPECT_FLOAT_EQ(chooseCamera(s, "Wide").yfov, 0.6f);    // the camera's own name
  EXPECT_FLOAT_EQ(chooseCamera(s, "Second").yfov, 0.6f);  // its node's
}

TEST(GltfCameras, UnknownIndexOrNameListsTheCameras) {
  const Scene s = threeCameras();
  for (const std::string which : {"3", "99", "Fourth", "0x1"}) {
    const std::string e = errorOf(s, which);
    EXPECT_NE(e.find("cams.gltf: --camera"), std::string::npos) << e;
    EXPECT_NE(e.find(which), std::string::npos) << e;
    EXPECT_NE(e.find("2 (node \"Third\"), 0 (node \"First\"), 1 \"Wide\" (node \"Second\")"),
              std::string::npos)
        << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  }
}

/// One perspective camera with `ext` as its TRAY_camera object.
Scene lensCamera(const std::string& ext) {
  return loadJson(R"({"asset":{"version":"2.0"},"scenes":[{"nodes":[0]}],"nodes":[{"camera":0}],
    "extensionsUsed":["TRAY_camera"],
    "cameras":[{"type":"perspective","perspective":{"yfov":0.5,"znear":0.1},
                "extensions":{"TRAY_camera":)" +
                  ext + "}}]}");
}

TEST(GltfCameras, TrayCameraStatesTheThinLens) {
  const CameraDesc c =
      lensCamera(R"({"lensRadius":0.05,"focusDistance":4,"apertureBlades":6})").cameras.at(0);
  EXPECT_FLOAT_EQ(c.lensRadius, 0.05f);
  EXPECT_FLOAT_EQ(c.focusDistance, 4.0f);
  EXPECT_EQ(c.apertureBlades, 6);
  for (const char* bad :
       {R"({"lensRadius":0.05})", R"({"lensRadius":0.1,"focusDistance":2,"apertureBlades":2})",
        R"({"lensradius":0.1})", R"({"lensRadius":-1,"focusDistance":2})"}) {
    try {
      lensCamera(bad);
      ADD_FAILURE() << bad << " was accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("TRAY_camera"), std::string::npos) << e.what();
    }
  }
}

TEST(GltfCameras, LensOptionsOverrideTrayCamera) {
  CameraDesc c = lensCamera(R"({"lensRadius":0.05,"focusDistance":4})").cameras.at(0);
  RenderSettings st;
  st.set("focus-distance", 2.5f);
  applyLensOptions(c, st);
  EXPECT_FLOAT_EQ(c.lensRadius, 0.05f);  // not set: the camera's
  EXPECT_FLOAT_EQ(c.focusDistance, 2.5f);
  st.set("lens-radius", 0.0f);
  applyLensOptions(c, st);
  EXPECT_EQ(c.lensRadius, 0.0f);  // --lens-radius 0: a pinhole whatever the file says
  st.set("aperture-blades", 2);
  EXPECT_THROW(applyLensOptions(c, st), Error);
  CameraDesc pinhole;
  RenderSettings radiusOnly;
  radiusOnly.set("lens-radius", 0.1f);
  EXPECT_THROW(applyLensOptions(pinhole, radiusOnly), Error);
}

TEST(GltfCameras, KhronosCamerasSample) {
  // Cameras.gltf: cameras[0] perspective, cameras[1] orthographic, placed in that order.
  Scene s = loadGltf(TRAY_SHARED_DIR "/gltf-samples/Cameras.gltf");
  EXPECT_EQ(chooseCamera(s, "0").type, CameraDesc::Type::kPerspective);
  EXPECT_EQ(chooseCamera(s, "1").type, CameraDesc::Type::kOrthographic);
  EXPECT_EQ(chooseCamera(s, "").type, CameraDesc::Type::kPerspective);
  EXPECT_NE(errorOf(s, "2").find("0, 1"), std::string::npos) << errorOf(s, "2");
}

}  // namespace
}  // namespace tray
