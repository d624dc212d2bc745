// Farm rendering end to end through the real binaries: region and sample-range parts merged by
// tray-merge against one full render, usage errors, interruption by a real SIGINT / SIGTERM,
// checkpoints and --resume (docs/farm.md).
#include <OpenImageIO/imagebuf.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>
#include <thread>

#include "tests/cli/cli_run.h"

namespace tray::test {
namespace {

const std::string kCornell = std::string(TRAY_SHARED_DIR) + "/reference/cornell-box.gltf";
const std::string kWhitted = std::string(TRAY_SOURCE_DIR) + "/scenes/whitted.gltf";
// Path tracing, 8 jittered samples through a tent filter (overlapping support: samples land
// outside their pixel, which regions must not change), with every AOV but Cryptomatte, whose
// ranked coverage cannot be split by samples (tray-render refuses it with --sample-range).
const std::string kBaseJob = "'" + kCornell + "' --integrator path --spp 8 --filter tent";
const std::string kSmallJob =
    kBaseJob + " --aov depth,normal,position,albedo,objectid,materialid,samples";
// Long enough to interrupt from outside (interruptCli): on one thread, 7x6 tiles of about 23 ms
// (16x16 pixels x 192 samples; the ones on the right and bottom edges cut), i.e. about 1 s left
// after the first tile, when the signal is sent.
const std::string kLongJob = "'" + kCornell +
                             "' --integrator path --spp 192 --filter tent --aov depth,normal,"
                             "position,albedo,objectid,materialid,samples --seed 7 --resolution "
                             "101x93";
// Regions keep every pixel whole, so they merge Cryptomatte layers too.
const std::string kJobAllAovs = kBaseJob + " --aov all --seed 7 --resolution 37x29";

std::string out(const fs::path& dir, const std::string& name) {
  return "-o '" + (dir / name).string() + "'";
}

TEST(Farm, FourRegionsMergeBitForBit) {
  const fs::path dir = testDir();
  ASSERT_EQ(runCli(TRAY_RENDER_BIN, kJobAllAovs + " " + out(dir, "full.exr"), dir).exitCode, 0);
  // "all" is all: with the path tracer the light-path layers are there too.
  EXPECT_NE(readExrFile(dir / "full.exr").spec.channelindex("diffuse_direct.R"), -1);
  // Uneven quadrants that cut through 16-pixel tiles.
  const char* regions[] = {"0,0,13,11", "13,0,37,11", "0,11,13,29", "13,11,37,29"};
  std::string parts;
  for (int i = 0; i < 4; ++i) {
    const std::string name = std::string("r") + char('0' + i) + ".exr";
    CliResult r = runCli(TRAY_RENDER_BIN,
                         kJobAllAovs + " --region " + regions[i] + " " + out(dir, name), dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    parts += " '" + (dir / name).string() + "'";
  }
  // A region part is the crop as a data window of the full display window.
  const Exr r3 = readExrFile(dir / "r3.exr");
  EXPECT_EQ(r3.spec.x, 13);
  EXPECT_EQ(r3.spec.y, 11);
  EXPECT_EQ(r3.spec.width, 24);
  EXPECT_EQ(r3.spec.height, 18);
  EXPECT_EQ(r3.spec.full_width, 37);
  EXPECT_EQ(r3.spec.full_height, 29);
  const Exr full = readExrFile(dir / "full.exr");
  EXPECT_EQ(r3.at(0, 0, "R"), full.at(13, 11, "R"));

  CliResult m = runMerge(parts + " " + out(dir, "merged.exr"), dir);
  ASSERT_EQ(m.exitCode, 0) << m.err;
  expectSamePixels(full, readExrFile(dir / "merged.exr"), "4 regions merged");
}

TEST(Farm, AdaptiveRegionsMergeBitForBit) {
  // Robust adaptive sampling looks at the 8 tiles around each pixel's: across region borders too.
  const fs::path dir = testDir();
  const std::string job =
      "'" + kWhitted + "' --integrator adaptive --aa-robust --resolution 40x30 --aov samples";
  expectRegionsMergeToWhole(job, {"0,0,40,13", "0,13,40,30"}, dir, "adaptive");
}

/// Largest difference in units in the last place between two floats of the same sign.
int ulps(float a, float b) {
  int32_t ia, ib;
  std::memcpy(&ia, &a, 4);
  std::memcpy(&ib, &b, 4);
  return std::abs(ia - ib);
}

TEST(Farm, FourSampleRangesMergeWithinFloatRounding) {
  const fs::path dir = testDir();
  const std::string job = kBaseJob +
                          " --aov depth,normal,position,albedo,objectid,materialid,samples,"
                          "lightpaths --seed 7 --resolution 37x29 --float";
  ASSERT_EQ(runCli(TRAY_RENDER_BIN, job + " " + out(dir, "full.exr"), dir).exitCode, 0);
  const char* ranges[] = {"0,2", "2,3", "3,7", "7,8"};
  std::string parts, reversed;
  double cpuSeconds = 0;  // the parts' render CPU time, which the merge adds up
  for (int i = 0; i < 4; ++i) {
    const std::string name = std::string("s") + char('0' + i) + ".exr";
    CliResult r =
        runCli(TRAY_RENDER_BIN, job + " --sample-range " + ranges[i] + " " + out(dir, name), dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    cpuSeconds += readExrFile(dir / name).spec.get_float_attribute("tray:renderCpuSeconds");
    parts += " '" + (dir / name).string() + "'";
    reversed = " '" + (dir / name).string() + "'" + reversed;
  }
  ASSERT_EQ(runMerge(parts + " " + out(dir, "merged.exr"), dir).exitCode, 0);
  ASSERT_EQ(runMerge(reversed + " " + out(dir, "reversed.exr"), dir).exitCode, 0);
  const Exr full = readExrFile(dir / "full.exr"), merged = readExrFile(dir / "merged.exr");
  // The argument order does not matter: parts are added in sample order.
  expectSamePixels(merged, readExrFile(dir / "reversed.exr"), "merge order");
  ASSERT_EQ(full.spec.channelnames, merged.spec.channelnames);
  int worst = 0;
  size_t exact = 0, values = 0, averaged = 0;
  for (int y = 0; y < full.spec.height; ++y)
    for (int x = 0; x < full.spec.width; ++x)
      for (const std::string& c : full.spec.channelnames) {
        const float a = full.at(x, y, c), b = merged.at(x, y, c);
        if (c == "R" || c == "G" || c == "B" || c == "A") {  // sums of parts: rounding differs
          worst = std::max(worst, ulps(a, b));
          exact += a == b, ++values;
        } else if (c == "Z" || c[0] == 'N' || c.rfind("albedo", 0) == 0 || c.find('_') != c.npos ||
                   c.rfind("emission", 0) == 0 || c.rfind("transmission", 0) == 0 ||
                   c.rfind("background", 0) == 0) {
          // Averaged over every sample: the parts' means weighted by their filter-weight sums.
          if (a != b) {
            EXPECT_NEAR(a, b, 1e-6f + 1e-5f * std::fabs(a)) << c << " at " << x << "," << y;
          }
          averaged += a != 0;
        } else {  // AOVs of sample 0, and the summed sample count
          EXPECT_EQ(std::memcmp(&a, &b, 4), 0) << c << " at " << x << "," << y;
        }
      }
  EXPECT_LE(worst, 1) << "beauty differs by more than float rounding";
  EXPECT_GT(averaged, size_t(37 * 29));  // the averaged layers were compared, not all zero
  // The merged image did every sample of every pixel: the parts' counts added up.
  EXPECT_EQ(merged.spec.get_float_attribute("tray:samplesDone"), 37.0f * 29.0f * 8.0f);
  EXPECT_EQ(merged.spec.get_float_attribute("tray:samplesDone"),
            full.spec.get_float_attribute("tray:samplesDone"));
  EXPECT_GT(cpuSeconds, 0.0);
  EXPECT_FLOAT_EQ(merged.spec.get_float_attribute("tray:renderCpuSeconds"), float(cpuSeconds));
  EXPECT_GT(double(exact) / values, 0.99);
  std::printf("sample-range merge: %zu of %zu beauty values bit-identical, worst %d ulp\n", exact,
              values, worst);
}

/// The two sample-range parts 0,4.exr and 4,8.exr of `job` in `dir`; false if one failed.
bool renderTwoParts(const std::string& job, const fs::path& dir) {
  for (const char* range : {"0,4", "4,8"})
    if (runCli(TRAY_RENDER_BIN,
               job + " --sample-range " + range + " " + out(dir, std::string(range) + ".exr"), dir)
            .exitCode != 0)
      return false;
  return true;
}

TEST(Farm, MergeRefusesIncompleteOrForeignParts) {
  const fs::path dir = testDir();
  const std::string job = kSmallJob + " --resolution 40x8";  // 3 tiles
  ASSERT_TRUE(renderTwoParts(job, dir));
  ASSERT_EQ(
      runCli(TRAY_RENDER_BIN, job + " --seed 8 --sample-range 4,8 " + out(dir, "seed8.exr"), dir)
          .exitCode,
      0);
  // The same samples drawn from the other random sequence belong to another render.
  ASSERT_EQ(runCli(TRAY_RENDER_BIN,
                   job + " --sampler independent --sample-range 4,8 " + out(dir, "indep.exr"), dir)
                .exitCode,
            0);
  // An integrator option (declared in path.cpp only) is part of the job too.
  ASSERT_EQ(runCli(TRAY_RENDER_BIN,
                   job + " --max-depth 3 --sample-range 4,8 " + out(dir, "depth3.exr"), dir)
                .exitCode,
            0);
  // The output's precision is the job's: a float part does not merge with half ones.
  ASSERT_EQ(
      runCli(TRAY_RENDER_BIN, job + " --float --sample-range 4,8 " + out(dir, "float.exr"), dir)
          .exitCode,
      0);
  // The same scene file name with other bytes (one space added) is another scene.
  fs::create_directories(dir / "edited");
  const fs::path edited = dir / "edited" / fs::path(kCornell).filename();
  fs::copy_file(kCornell, edited);
  std::ofstream(edited, std::ios::app) << " ";
  std::string editedJob = job;
  editedJob.replace(editedJob.find(kCornell), kCornell.size(), edited.string());
  ASSERT_EQ(
      runCli(TRAY_RENDER_BIN, editedJob + " --sample-range 4,8 " + out(dir, "edited.exr"), dir)
          .exitCode,
      0);
  // A part of another job whose pixels cannot be read: refused by its header alone.
  {
    const std::string bytes = [&] {
      std::ifstream f(dir / "seed8.exr", std::ios::binary);
      return std::string(std::istreambuf_iterator<char>(f), {});
    }();
    std::ofstream(dir / "truncated.exr", std::ios::binary) << bytes.substr(0, bytes.size() - 200);
  }
  ASSERT_EQ(runCli(TRAY_RENDER_BIN, job + " " + out(dir, "full.exr"), dir).exitCode, 0);
  // A part interrupted after its first tile (refused by its header before the jobs are
  // compared: a longer job than this test's, which is too short to interrupt from outside).
  ASSERT_EQ(interruptCli(kLongJob + " --sample-range 4,192 " + out(dir, "unfinished.exr")).exitCode,
            130);
  const std::string a = "'" + (dir / "0,4.exr").string() + "'",
                    b = "'" + (dir / "4,8.exr").string() + "'";
  struct Case {
    std::string parts, says;
  } cases[] = {
      {a, "a part is missing"},
      {a + " " + b + " " + b, "renders too"},
      {a + " '" + (dir / "seed8.exr").string() + "'", "seed is '8' there"},
      {a + " '" + (dir / "float.exr").string() + "'", "output is 'float,default' there"},
      {a + " '" + (dir / "edited.exr").string() + "'", "content is"},
      {a + " '" + (dir / "truncated.exr").string() + "'", "another render"},
      {a + " '" + (dir / "indep.exr").string() + "'", "another render"},
      {a + " '" + (dir / "depth3.exr").string() + "'", "another render"},
      {"'" + (dir / "full.exr").string() + "'", "not a part"},
      {a + " '" + (dir / "unfinished.exr").string() + "'", "unfinished part"},
  };
  for (const Case& c : cases) {
    CliResult r = runMerge(c.parts + " " + out(dir, "m.exr"), dir);
    EXPECT_EQ(r.exitCode, 2) << c.parts;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  EXPECT_FALSE(fs::exists(dir / "m.exr"));
}

TEST(Farm, MergeNeverWritesOverAPart) {
  const fs::path dir = testDir();
  ASSERT_TRUE(renderTwoParts(kSmallJob + " --resolution 40x8", dir));
  const fs::path part = dir / "0,4.exr";
  const auto bytes = [](const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(f), {});
  };
  const std::string before = bytes(part);
  fs::create_symlink(part, dir / "link.exr");
  std::string parts = quoted(part);  // piecewise: GCC 12 warns falsely on "lit" + string&&
  parts += ' ';
  parts += quoted(dir / "4,8.exr");
  parts += ' ';
  // The part by its own name, by another spelling of it, and through a link.
  for (const std::string& output :
       {part.string(), (dir / "." / "0,4.exr").string(), (dir / "link.exr").string()}) {
    CliResult r = runMerge(parts + "-o '" + output + "'", dir);
    EXPECT_EQ(r.exitCode, 2) << output;
    EXPECT_NE(r.err.find("the output is also a part"), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  EXPECT_EQ(bytes(part), before);  // the part untouched
  // No parts at all: one line, in tray-merge's own form.
  CliResult none = runMerge(out(dir, "m.exr"), dir);
  EXPECT_EQ(none.exitCode, 2);
  EXPECT_EQ(none.err.rfind("tray-merge: error: ", 0), 0u) << none.err;
  EXPECT_EQ(std::count(none.err.begin(), none.err.end(), '\n'), 1) << none.err;
  // The merge itself still works.
  EXPECT_EQ(runMerge(parts + out(dir, "m.exr"), dir).exitCode, 0);
}

TEST(Farm, PlainProgressIsOneParseableLinePerStep) {
  const fs::path dir = testDir();
  // 64x48: 12 tiles of 16x16; a line each 25% (and none by time), the last at 100%.
  CliResult r = runTool(TRAY_RENDER_BIN,
                        "'" + kWhitted +
                            "' --resolution 64x48 --progress plain --progress-step 25 "
                            "--progress-seconds 0 " +
                            out(dir, "p.exr"),
                        dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  std::istringstream lines(r.err);
  std::string line;
  std::vector<double> percents;
  while (std::getline(lines, line)) {
    double percent = 0, elapsed = 0, eta = 0;
    char tail = 0;
    ASSERT_EQ(std::sscanf(line.c_str(), "progress %lf%% elapsed %lf s eta %lf s%c", &percent,
                          &elapsed, &eta, &tail),
              3)
        << "not a progress line: '" << line << "'";
    percents.push_back(percent);
  }
  EXPECT_EQ(percents, (std::vector<double>{25, 50, 75, 100}));
  // A bad mode is a usage error before any work.
  CliResult bad =
      runTool(TRAY_RENDER_BIN, "'" + kWhitted + "' --progress fancy " + out(dir, "x.exr"), dir);
  EXPECT_EQ(bad.exitCode, 2);
  EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
}

TEST(Farm, BadRegionsAndRangesAreUsageErrors) {
  const fs::path dir = testDir();
  const std::string job = "'" + kWhitted + "' --resolution 32x24 ";
  const std::string exr = out(dir, "x.exr");
  for (const std::string& bad :
       {"--region 0,0,33,24 " + exr, "--region 5,5,5,9 " + exr, "--region -1,0,4,4 " + exr,
        "--region 1,2,3 " + exr, "--region a,b,c,d " + exr, "--sample-range 0,2 " + exr,
        "--spp 4 --sample-range 3,2 " + exr, "--integrator adaptive --sample-range 0,1 " + exr,
        "--spp 4 --sample-range 0,2 --aov cryptomatte " + exr,
        "--checkpoint 5 " + out(dir, "x.png"), "--checkpoint nan " + exr,
        "--checkpoint inf " + exr}) {
    CliResult r = runCli(TRAY_RENDER_BIN, job + bad, dir);
    EXPECT_EQ(r.exitCode, 2) << bad;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << bad << ": " << r.err;
  }
  EXPECT_FALSE(fs::exists(dir / "x.exr"));
  EXPECT_FALSE(fs::exists(dir / "x.png"));
}

/// An interrupted render (a real SIGINT sent by interruptCli after its first tile), resumed,
/// equals the uninterrupted one bit for bit; the partial file marks its unfinished pixels.
void interruptAndResume(const std::string& job) {
  const fs::path dir = testDir();
  ASSERT_EQ(runCli(TRAY_RENDER_BIN, job + " " + out(dir, "full.exr"), dir).exitCode, 0);
  CliResult r = interruptCli(job + " " + out(dir, "part.exr"));
  ASSERT_EQ(r.exitCode, 130) << r.err;
  const Exr partial = readExrFile(dir / "part.exr");
  EXPECT_EQ(partial.spec.get_string_attribute("tray:status"), "partial");
  const float done = partial.spec.get_float_attribute("tray:pixelsDone");
  const int pixels = partial.spec.width * partial.spec.height;
  EXPECT_GE(done, 1.0f);
  EXPECT_LT(done, float(pixels));
  const float perPixel = partial.spec.get_float_attribute("tray:sampleEnd") -
                         partial.spec.get_float_attribute("tray:sampleBegin");
  if (partial.spec.get_float_attribute("tray:samplesPerPixel") > 0) {
    EXPECT_EQ(partial.spec.get_float_attribute("tray:samplesDone"), done * perPixel);
  }
  size_t marked = 0, alphaZero = 0;
  for (int y = 0; y < partial.spec.height; ++y)
    for (int x = 0; x < partial.spec.width; ++x)
      if (partial.at(x, y, "tray.done") == 0) ++marked, alphaZero += partial.at(x, y, "A") == 0;
  EXPECT_EQ(marked, size_t(pixels - done));
  EXPECT_EQ(alphaZero, marked);
  std::printf("interrupted after %g of %d pixels\n", double(done), pixels);

  r = runCli(TRAY_RENDER_BIN, job + " --resume " + out(dir, "part.exr"), dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const Exr resumed = readExrFile(dir / "part.exr");
  EXPECT_EQ(resumed.spec.get_string_attribute("tray:status"), "complete");
  expectSamePixels(readExrFile(dir / "full.exr"), resumed, "resumed");
  // Resuming what is finished changes nothing; resuming with no file renders from the start.
  r = runCli(TRAY_RENDER_BIN, job + " --resume " + out(dir, "part.exr"), dir);
  EXPECT_EQ(r.exitCode, 0) << r.err;
  expectSamePixels(readExrFile(dir / "full.exr"), readExrFile(dir / "part.exr"), "resumed twice");
  r = runCli(TRAY_RENDER_BIN, job + " --resume " + out(dir, "fresh.exr"), dir);
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("no checkpoint"), std::string::npos) << r.err;
  expectSamePixels(readExrFile(dir / "full.exr"), readExrFile(dir / "fresh.exr"), "fresh");
  // A checkpoint of another render is refused.
  r = runCli(TRAY_RENDER_BIN, job + " --seed 99 --resume " + out(dir, "part.exr"), dir);
  EXPECT_EQ(r.exitCode, 2);
}

// Issue 40: a checkpoint whose tray.done channel was edited (pixels marked done that were
// never rendered) resumed, and the image was labelled complete. The channel is now checked
// against the header written with it.
TEST(Farm, ResumeRefusesACheckpointWhoseDoneChannelWasEdited) {
  const fs::path dir = testDir();
  CliResult r = interruptCli(kLongJob + " " + out(dir, "part.exr"));
  ASSERT_EQ(r.exitCode, 130) << r.err;
  const std::string path = (dir / "part.exr").string();
  OIIO::ImageBuf edited(path);
  ASSERT_TRUE(edited.read(0, 0, true));
  const int done = edited.spec().channelindex("tray.done");
  ASSERT_GE(done, 0);
  for (OIIO::ImageBuf::Iterator<float> it(edited); !it.done(); ++it) it[done] = 1.0f;
  ASSERT_TRUE(edited.write(path + ".tmp.exr"));
  fs::rename(path + ".tmp.exr", path);
  r = runCli(TRAY_RENDER_BIN, kLongJob + " --resume " + out(dir, "part.exr"), dir);
  EXPECT_EQ(r.exitCode, 2) << r.err;
  EXPECT_NE(r.err.find("tray.done channel marks"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(readExrFile(dir / "part.exr").spec.get_string_attribute("tray:status"), "partial");
}

TEST(Farm, InterruptedPathRenderResumesBitForBit) {
  interruptAndResume(kLongJob);
}

TEST(Farm, InterruptedRegionSampleRangeResumesBitForBit) {
  interruptAndResume(kLongJob + " --region 3,4,100,92 --sample-range 4,192");  // 7x6 tiles
}

TEST(Farm, InterruptedAdaptiveRenderResumesBitForBit) {
  // 7x5 tiles of about 33 ms on one thread (a low threshold and one more level: more squares).
  interruptAndResume("'" + kWhitted +
                     "' --integrator adaptive --resolution 100x75 --aa-threshold 0.005 "
                     "--aa-depth 5 --aov samples");
}

/// Waits until `path` exists (a checkpoint was written) or the child exits.
bool waitForFile(const fs::path& path, pid_t child) {
  for (int i = 0; i < 30000; ++i) {
    if (fs::exists(path)) return true;
    int status;
    if (waitpid(child, &status, WNOHANG) == child) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return false;
}

/// Waits until the child catches SIGINT and SIGTERM (/proc/PID/status SigCgt), i.e. a signal
/// now reaches tray-render's handler instead of killing it; false if it exits first.
bool waitForHandlers(pid_t child) {
  const uint64_t wanted = 1ull << (SIGINT - 1) | 1ull << (SIGTERM - 1);
  for (int i = 0; i < 60000; ++i) {
    std::ifstream status("/proc/" + std::to_string(child) + "/status");
    std::string line;
    while (std::getline(status, line))
      if (line.rfind("SigCgt:", 0) == 0 &&
          (std::stoull(line.substr(7), nullptr, 16) & wanted) == wanted)
        return true;
    int st;
    if (waitpid(child, &st, WNOHANG) == child) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return false;
}

TEST(Farm, RealSignalsExit130And143WithThePartialImage) {
  for (int sig : {SIGINT, SIGTERM}) {
    const fs::path dir = testDir();
    const fs::path image = dir / ("long-" + std::to_string(sig) + ".exr");
    // A good PNG from an earlier render: a display-referred output, which nothing could mark
    // partial, is never replaced by an interrupted render (issue 40); it goes beside it.
    const fs::path png = dir / "good.png", partialPng = dir / "good.partial.png";
    std::ofstream(png, std::ios::binary) << "an earlier, complete image";
    // Far too long to finish (hours): it stops only because of the signal.
    const pid_t child =
        spawnRender({kCornell, "--integrator", "path", "--resolution", "32x32", "--spp", "1000000",
                     "-q", "-o", image.string(), "-o", png.string()});
    ASSERT_TRUE(waitForHandlers(child)) << "tray-render exited before installing its handlers";
    std::this_thread::sleep_for(std::chrono::milliseconds(200));  // let it start rendering
    kill(child, sig);
    EXPECT_EQ(waitExit(child), 128 + sig);
    const Exr partial = readExrFile(image);
    EXPECT_EQ(partial.spec.get_string_attribute("tray:status"), "partial");
    EXPECT_LT(partial.spec.get_float_attribute("tray:pixelsDone"), 32.0f * 32.0f);
    std::ifstream kept(png, std::ios::binary);
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(kept), {}), "an earlier, complete image");
    EXPECT_TRUE(fs::exists(partialPng));
  }
}

TEST(Farm, CheckpointSurvivesSigkillAndResumesBitForBit) {
  const fs::path dir = testDir();
  const std::string args[] = {kCornell, "--integrator", "path",  "--resolution", "48x48",
                              "--spp",  "96",           "--aov", "depth,normal"};
  std::string job;
  for (const auto& a : args) job += "'" + a + "' ";
  ASSERT_EQ(runCli(TRAY_RENDER_BIN, job + out(dir, "full.exr"), dir).exitCode, 0);
  const fs::path image = dir / "crash.exr";
  std::vector<std::string> argv(std::begin(args), std::end(args));
  for (const char* a : {"--checkpoint", "0.01", "-q", "-o"}) argv.push_back(a);
  argv.push_back(image.string());
  const pid_t child = spawnRender(argv);
  ASSERT_TRUE(waitForFile(image, child)) << "the render ended before its first checkpoint";
  kill(child, SIGKILL);  // a machine that dies: only the last checkpoint is left
  EXPECT_EQ(waitExit(child), -SIGKILL);
  const Exr checkpoint = readExrFile(image);
  EXPECT_EQ(checkpoint.spec.get_string_attribute("tray:status"), "partial");
  CliResult r = runCli(TRAY_RENDER_BIN, job + "--resume -o '" + image.string() + "'", dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  expectSamePixels(readExrFile(dir / "full.exr"), readExrFile(image), "resumed after SIGKILL");
}

}  // namespace
}  // namespace tray::test
