// Output mistakes are reported before the scene is even loaded: each case names a scene that
// does not exist, so an error about the output (not the scene) proves the output was checked
// first. One line, exit 2, nothing written. On a farm this is the difference between failing
// at once and failing hours later, after the render.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/temp_dir.h"

namespace fs = std::filesystem;

namespace {

struct Case {
  const char* name;
  std::string args;
  const char* expected;  ///< part of the one error line
};

std::string runTray(const std::string& args, int& code) {
  const fs::path err = tray::test::testDir() / "stderr.txt";
  const std::string cmd =
      std::string(TRAY_RENDER_BIN) + " -q /nonexistent/scene.gltf " + args + " 2>" + err.string();
  const int status = std::system(cmd.c_str());
  code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(err);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(CliOutputCheck, MistakesAreReportedBeforeTheSceneIsRead) {
  // The test's own folder: a stray x.exr left in a shared temp folder failed the last check.
  const std::string tmp = tray::test::testDir().string();
  const Case cases[] = {
      {"extension", "-o " + tmp + "/x.tiff", "unsupported output format '.tiff'"},
      {"folder", "-o /nonexistent-folder/x.exr", "folder '/nonexistent-folder' does not exist"},
      {"colorspace", "-o " + tmp + "/x.exr --output-colorspace NoSuchSpace",
       "unknown colorspace 'NoSuchSpace'"},
      {"display", "-o " + tmp + "/x.png --display NoSuchDisplay", "unknown display"},
      {"view", "-o " + tmp + "/x.png --view NoSuchView", "unknown view"},
      {"heatmap", "-o " + tmp + "/x.exr --aa-heatmap " + tmp + "/h.bmp", "h.bmp"},
      {"ocio", "-o " + tmp + "/x.exr", "OpenColorIO config not found"},
  };
  for (const Case& c : cases) {
    const bool badConfig = std::string(c.name) == "ocio";
    if (badConfig) setenv("OCIO", "/nonexistent/config.ocio", 1);
    int code = 0;
    const std::string err = runTray(c.args, code);
    if (badConfig) unsetenv("OCIO");
    EXPECT_EQ(code, 2) << c.name << ": " << err;
    EXPECT_NE(err.find(c.expected), std::string::npos) << c.name << ": " << err;
    EXPECT_EQ(err.find("scene.gltf"), std::string::npos) << c.name << ": scene read first: " << err;
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << c.name << ": " << err;
  }
  EXPECT_FALSE(fs::exists(tmp + "/x.exr"));
}

}  // namespace
