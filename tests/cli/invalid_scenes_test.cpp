// The command line on every file of shared/gltf-samples/invalid/: exit code 2 (bad input) and
// exactly one line on stderr, which names the file; no output image is left behind.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "tests/temp_dir.h"

namespace fs = std::filesystem;

namespace {

const fs::path kInvalidDir = fs::path(TRAY_SHARED_DIR) / "gltf-samples" / "invalid";

std::vector<std::string> invalidFiles() {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(kInvalidDir, ec))
    if (e.is_regular_file()) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

/// Single-quotes a path for /bin/sh.
std::string quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

class CliInvalidScene : public ::testing::TestWithParam<std::string> {};

TEST_P(CliInvalidScene, ExitsWithCode2AndOneLineNamingTheFile) {
  const fs::path dir = tray::test::testDir();
  const fs::path out = dir / (GetParam() + ".exr"), err = dir / (GetParam() + ".stderr");
  const std::string scene = (kInvalidDir / GetParam()).string();
  const std::string cmd = quoted(TRAY_RENDER_BIN) + " -q --resolution 8x8 -o " +
                          quoted(out.string()) + " " + quoted(scene) + " 2>" + quoted(err.string());
  const int status = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(status)) << cmd;
  EXPECT_EQ(WEXITSTATUS(status), 2) << cmd;
  std::ifstream in(err);
  std::stringstream text;
  text << in.rdbuf();
  const std::string s = text.str();
  ASSERT_FALSE(s.empty());
  EXPECT_EQ(std::count(s.begin(), s.end(), '\n'), 1) << s;
  EXPECT_EQ(s.back(), '\n') << s;
  EXPECT_NE(s.find(GetParam()), std::string::npos) << s;
  EXPECT_FALSE(fs::exists(out));
}

std::string testName(const ::testing::TestParamInfo<std::string>& info) {
  std::string name = info.param;
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(SharedSamples, CliInvalidScene, ::testing::ValuesIn(invalidFiles()),
                         testName);

TEST(CliInvalidSceneFolder, IsNotEmpty) {
  EXPECT_GE(invalidFiles().size(), 20u);
}

}  // namespace
