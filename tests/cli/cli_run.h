#pragma once
// Running the real command-line tools from tests: exit status, stderr, child processes for
// signals, and EXR files read back with OIIO (independently of TRay's own reader).
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "tests/exr_read.h"
#include "tests/temp_dir.h"

namespace tray::test {

namespace fs = std::filesystem;

struct CliResult {
  int exitCode = -1;
  std::string err;
};

/// 'path' for /bin/sh (appended piecewise: GCC 12 warns falsely on "lit" + std::string&&).
inline std::string quoted(const fs::path& path) {
  std::string s = "'";
  s += path.string();
  s += "'";
  return s;
}

/// Runs `binary args` through the shell (args already quoted), stderr captured.
inline CliResult runTool(const std::string& binary, const std::string& args, const fs::path& dir) {
  const fs::path errFile = dir / "stderr.txt";
  std::string cmd = "'";  // appended piecewise: GCC 12 warns falsely on "lit" + std::string&&
  cmd += binary;
  cmd += "' ";
  cmd += args;
  cmd += " 2> '";
  cmd += errFile.string();
  cmd += "'";
  const int status = std::system(cmd.c_str());
  std::ifstream f(errFile);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, {std::istreambuf_iterator<char>(f), {}}};
}

/// tray-render (quiet) or another tool with `args`.
inline CliResult runCli(const std::string& binary, const std::string& args, const fs::path& dir) {
  return runTool(binary, args + " -q", dir);
}
inline CliResult runMerge(const std::string& args, const fs::path& dir) {
  return runTool(TRAY_MERGE_BIN, args, dir);
}

/// Starts tray-render with `args` (one argv entry each) as a child process, output silenced.
inline pid_t spawnRender(const std::vector<std::string>& args) {
  const pid_t pid = fork();
  if (pid == 0) {
    std::vector<char*> argv{const_cast<char*>(TRAY_RENDER_BIN)};
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    freopen("/dev/null", "w", stdout);
    freopen("/dev/null", "w", stderr);
    execv(TRAY_RENDER_BIN, argv.data());
    _exit(127);
  }
  return pid;
}

/// The exit code of a child (waits for it); -signal if a signal ended it.
inline int waitExit(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
}

/// Same channels, windows and pixel bits (memcmp: NaN-safe, -0 differs from +0).
inline void expectSamePixels(const Exr& a, const Exr& b, const std::string& what) {
  ASSERT_EQ(a.spec.channelnames, b.spec.channelnames) << what;
  ASSERT_EQ(a.spec.width, b.spec.width) << what;
  ASSERT_EQ(a.spec.height, b.spec.height) << what;
  EXPECT_EQ(a.spec.x, b.spec.x) << what;
  EXPECT_EQ(a.spec.full_width, b.spec.full_width) << what;
  for (int c = 0; c < a.spec.nchannels; ++c)
    EXPECT_EQ(a.spec.channelformat(c), b.spec.channelformat(c));
  size_t differ = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i)
    differ += std::memcmp(&a.pixels[i], &b.pixels[i], sizeof(float)) != 0;
  EXPECT_EQ(differ, 0u) << what << ": " << differ << " of " << a.pixels.size() << " values differ";
}

}  // namespace tray::test
