// Every file in shared/gltf-samples/invalid/ must be refused with a one-line tray::Error naming
// the file: never a crash, never a scene.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "core/error.h"
#include "gltf/gltf_loader.h"

namespace tray {
namespace {

namespace fs = std::filesystem;

const fs::path kInvalidDir = fs::path(TRAY_SHARED_DIR) / "gltf-samples" / "invalid";

/// The folder is listed when the test binary starts, so a file added there is tested too.
std::vector<std::string> invalidFiles() {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(kInvalidDir, ec))
    if (entry.is_regular_file()) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

class GltfInvalid : public ::testing::TestWithParam<std::string> {};

TEST_P(GltfInvalid, RefusedWithOneLineError) {
  const std::string path = (kInvalidDir / GetParam()).string();
  LoadReport report;
  try {
    loadGltf(path, {}, &report);
    FAIL() << path << " loaded without error";
  } catch (const Error& e) {
    std::string message = e.what();
    EXPECT_NE(message.find(GetParam()), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_EQ(message.find('\r'), std::string::npos) << message;
    EXPECT_EQ(e.kind(), Error::Kind::kInput);
  }
}

TEST(GltfInvalidFolder, IsNotEmpty) {
  EXPECT_GE(invalidFiles().size(), 20u);
}

std::string testName(const ::testing::TestParamInfo<std::string>& info) {
  std::string name = info.param;
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(SharedSamples, GltfInvalid, ::testing::ValuesIn(invalidFiles()), testName);

}  // namespace
}  // namespace tray
