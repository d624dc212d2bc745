#pragma once
// One folder per test for the files it writes: <::testing::TempDir()>/<Suite>.<Test>, created
// fresh when the test first asks for it, removed when the test passes, kept (its path printed) when
// it fails. A passing run leaves nothing behind; a failing one leaves its evidence where the log
// says. Under ctest, TMPDIR points into the build tree (tests/CMakeLists.txt), so even files a
// test forgets never reach /tmp.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

namespace tray::test {

namespace detail {

/// Removes or reports the running test's folder when the test ends (a gtest listener: it runs
/// however the test ended, after a failed ASSERT too).
class TestDirCleaner : public ::testing::EmptyTestEventListener {
 public:
  void OnTestEnd(const ::testing::TestInfo& info) override {
    if (dir_.empty()) return;
    if (info.result()->Failed()) {
      std::printf("test files kept in %s\n", dir_.c_str());
    } else {
      std::error_code ec;  // a file held open elsewhere must not fail a passing test
      std::filesystem::remove_all(dir_, ec);
    }
    dir_.clear();
  }
  std::filesystem::path dir_;
};

/// The one cleaner, registered on first use (gtest owns and deletes its listeners).
inline TestDirCleaner& cleaner() {
  static TestDirCleaner* const instance = [] {
    auto* c = new TestDirCleaner;
    ::testing::UnitTest::GetInstance()->listeners().Append(c);
    return c;
  }();
  return *instance;
}

}  // namespace detail

/// The running test's own folder: empty at the test's first call, the same folder (with what the
/// test wrote) at later ones, so helpers may ask for it too.
inline std::filesystem::path testDir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string name = std::string(info->test_suite_name()) + "." + info->name();
  for (char& c : name)
    if (c == '/') c = '_';  // parameterized tests: Prefix/Suite.Name/0
  // ctest runs the path tests twice, as themselves and as "wavefront." (tests/CMakeLists.txt),
  // possibly at once under -j: each run its own folder, or one deletes the other's files.
  if (const char* variant = std::getenv("TRAY_TEST_PATH_INTEGRATOR"))
    name = std::string(variant) + "." + name;
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / name;
  if (detail::cleaner().dir_ == dir) return dir;
  std::filesystem::remove_all(dir);  // a folder kept by an earlier failed run
  std::filesystem::create_directories(dir);
  detail::cleaner().dir_ = dir;
  return dir;
}

}  // namespace tray::test
