#pragma once
// Running the real command-line tools from tests: exit status, stderr, child processes for
// signals, and EXR files read back with OIIO (independently of TRay's own reader).
#include <OpenImageIO/imageio.h>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
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

/// tray-render with `args` (shell-quoted, as for runCli), interrupted from outside by a real
/// SIGINT: it runs on one thread with a `--progress plain` line per tile on stderr (a pipe
/// read here line by line), and the signal is sent as soon as the first progress line is read,
/// i.e. after its first finished tile. The render must last long enough after that tile that
/// the signal cannot come after its last one (dozens of tiles of 10 ms or more); whatever tile
/// it lands after, at least one tile is done and the render is partial. tray-render runs at
/// nice 19, so that on a loaded machine it slows down rather than this process, whose
/// wake-up on the line is the time the signal takes. `err` is all of
/// tray-render's stderr, progress lines included (exit code -1: /bin/sh could not be started).
inline CliResult interruptCli(const std::string& args) {
  // exec, twice: the shell's pid becomes nice's, then tray-render's, the one signalled.
  std::string cmd = "exec nice -n 19 '";
  cmd += TRAY_RENDER_BIN;
  cmd += "' ";
  cmd += args;
  cmd += " --threads 1 --progress plain --progress-step 1 --progress-seconds 0";
  int pipeFds[2];
  if (pipe2(pipeFds, O_CLOEXEC) != 0) return {};
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  posix_spawn_file_actions_addopen(&files, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_adddup2(&files, pipeFds[1], 2);  // dup2 clears O_CLOEXEC on fd 2
  // Default dispositions and no blocked signal, whatever the test runner set for itself.
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  sigset_t none, defaults;
  sigemptyset(&none);
  sigemptyset(&defaults);
  sigaddset(&defaults, SIGINT);
  sigaddset(&defaults, SIGTERM);
  posix_spawnattr_setsigmask(&attr, &none);
  posix_spawnattr_setsigdefault(&attr, &defaults);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
  const char* argv[] = {"sh", "-c", cmd.c_str(), nullptr};
  pid_t pid = -1;
  const int spawned =
      posix_spawn(&pid, "/bin/sh", &files, &attr, const_cast<char* const*>(argv), environ);
  posix_spawn_file_actions_destroy(&files);
  posix_spawnattr_destroy(&attr);
  close(pipeFds[1]);  // EOF once tray-render exits
  CliResult result;
  if (spawned != 0) {
    close(pipeFds[0]);
    return result;
  }
  bool signalled = false;
  size_t lineStart = 0;
  char buffer[4096];
  for (;;) {
    const ssize_t n = read(pipeFds[0], buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    result.err.append(buffer, size_t(n));
    for (size_t end; !signalled && (end = result.err.find('\n', lineStart)) != std::string::npos;
         lineStart = end + 1)
      if (result.err.compare(lineStart, 9, "progress ") == 0) {
        kill(pid, SIGINT);
        signalled = true;
      }
  }
  close(pipeFds[0]);
  result.exitCode = waitExit(pid);
  return result;
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

/// Renders `job` whole (full.exr in `dir`) and as `regions` ("x0,y0,x1,y1" each), merges the
/// parts with tray-merge and expects the merge to hold the whole render's pixels bit for bit.
inline void expectRegionsMergeToWhole(const std::string& job,
                                      const std::vector<std::string>& regions,
                                      const fs::path& dir, const std::string& what) {
  // Appended piecewise: GCC 12 warns falsely on "lit" + std::string&& (see quoted()).
  auto output = [&](const std::string& name) {
    std::string o = " -o ";
    o += quoted(dir / name);
    return o;
  };
  ASSERT_EQ(runCli(TRAY_RENDER_BIN, job + output("full.exr"), dir).exitCode, 0);
  std::string parts;
  for (const std::string& region : regions) {
    std::string args = job;
    args += " --region ";
    args += region;
    args += output(region + ".exr");
    CliResult r = runCli(TRAY_RENDER_BIN, args, dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    parts += ' ';
    parts += quoted(dir / (region + ".exr"));
  }
  CliResult m = runMerge(parts + output("merged.exr"), dir);
  ASSERT_EQ(m.exitCode, 0) << m.err;
  expectSamePixels(readExrFile(dir / "full.exr"), readExrFile(dir / "merged.exr"), what);
}

}  // namespace tray::test
