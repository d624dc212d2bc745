// The scene content hash of farm job signatures: it follows the bytes of the scene file and of
// every file its URIs name, and nothing else (docs/farm.md, "What a part stores").
#include "gltf/scene_hash.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "tests/temp_dir.h"

namespace fs = std::filesystem;

namespace tray {
namespace {

void writeFile(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

TEST(SceneHash, FollowsTheSceneAndEveryFileItsUrisName) {
  const fs::path dir = test::testDir();
  fs::create_directories(dir / "tex");
  // A buffer whose URI is percent-encoded, an image in a subfolder, a data: URI.
  const std::string gltf =
      R"({"asset":{"version":"2.0"},"buffers":[{"uri":"geo%20a.bin","byteLength":4},)"
      R"({"uri":"data:application/octet-stream;base64,AAAA","byteLength":3}],)"
      R"("images":[{"uri":"tex/albedo.png"}]})";
  writeFile(dir / "scene.gltf", gltf);
  writeFile(dir / "geo a.bin", "abcd");
  writeFile(dir / "tex" / "albedo.png", "png1");
  writeFile(dir / "unrelated.bin", "zzzz");
  const std::string scene = (dir / "scene.gltf").string();
  const std::string first = sceneContentHash(scene, false);
  EXPECT_EQ(first.size(), 32u);
  EXPECT_EQ(sceneContentHash(scene, false), first);  // deterministic

  writeFile(dir / "unrelated.bin", "yyyy");  // not named by the scene
  EXPECT_EQ(sceneContentHash(scene, false), first);

  writeFile(dir / "geo a.bin", "abce");  // a buffer's byte
  const std::string buffer = sceneContentHash(scene, false);
  EXPECT_NE(buffer, first);

  writeFile(dir / "tex" / "albedo.png", "png2");  // an image's byte
  const std::string image = sceneContentHash(scene, false);
  EXPECT_NE(image, buffer);

  writeFile(dir / "scene.gltf", gltf + " ");  // the file itself, same name
  EXPECT_NE(sceneContentHash(scene, false), image);

  // A file of the same bytes elsewhere has the same hash: machines may mount scenes anywhere.
  fs::create_directories(dir / "copy" / "tex");
  for (const char* f : {"scene.gltf", "geo a.bin", "tex/albedo.png"})
    fs::copy_file(dir / f, dir / "copy" / f);
  EXPECT_EQ(sceneContentHash((dir / "copy" / "scene.gltf").string(), false),
            sceneContentHash(scene, false));
  EXPECT_THROW(sceneContentHash((dir / "missing.gltf").string(), false), std::exception);
}

// The --env map shapes the pixels but is no URI of the scene: an edited map under the same
// path must change the job's content hash, a copy elsewhere must not.
TEST(SceneHash, FollowsTheEnvironmentMapOutsideTheScene) {
  const fs::path dir = test::testDir();
  writeFile(dir / "scene.gltf", R"({"asset":{"version":"2.0"}})");
  writeFile(dir / "sky.exr", "sky1");
  const std::string scene = (dir / "scene.gltf").string(), sky = (dir / "sky.exr").string();
  const std::string alone = sceneContentHash(scene, false);
  const std::string lit = sceneContentHash(scene, false, {sky});
  EXPECT_NE(lit, alone);
  writeFile(dir / "sky.exr", "sky2");
  EXPECT_NE(sceneContentHash(scene, false, {sky}), lit);
  writeFile(dir / "copy.exr", "sky2");
  EXPECT_EQ(sceneContentHash(scene, false, {(dir / "copy.exr").string()}),
            sceneContentHash(scene, false, {sky}));
}

}  // namespace
}  // namespace tray
