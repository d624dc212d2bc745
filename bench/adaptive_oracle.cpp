// adaptive_oracle: how much lower relMSE than uniform sampling any UNBIASED per-pixel sample
// allocation can reach on a scene (issue 37; docs/bench/adaptive-oracle-2026-12-07.md).
//
// Renders the scene K times at `--spp` samples (TRay's default path tracer, Owen-scrambled
// Sobol', the sequence's pixel positions: what the sweep's "path sobol" renders), each with its
// own seed, so that every pixel has K independent means. The first half of the seeds (pool A)
// gives each pixel's relative variance a_i (bench/oracle_allocation.h) and from it the oracle
// allocation; the second half (pool B) is the samples the allocations spend: a pixel given k
// steps is the mean of its first k renders of pool B (each pixel's count is fixed before pool
// B is looked at, so every image is unbiased). Errors are taken by the sweep's own comparison
// (bench/image_error.cpp) against the sweep's reference (same settings and file name, so one
// reference serves both). Printed per budget (mean spp): the expected relMSE (pool B's
// variances) and the simulated relMSE and trimmed relMSE of uniform sampling and of:
//   oracle        n_i = clamp(lambda sqrt(a_i), spp, max) from pool A (1 step = --spp)
//   oracle-trim   the same, but the 0.1% pixels of largest a_i (those relMSE-trimmed drops
//                 anyway) held at one step
//   pilot P       a_i from the first P renders of pool A only (a pilot of P x spp samples per
//                 pixel, thrown away and paid for: the allocation gets P x spp fewer)
//   pilot P 3x3   the pilot's a_i averaged over the 3x3 neighbourhood first (5x5: over 5x5)
//   oracle of the 8 neighbours   pool A's a averaged over the 8 neighbours, the pixel left
//                 out: the best a rule that decides from its neighbours (TRay's default) can do
//   one-shot ...  every pixel takes P steps (kept), then its count in one go from the a_i of
//                 its neighbours' P steps (3x3 or 5x5 less itself): unbiased and implementable
// and then TRay's own threshold rules (--noise-decision neighbours, wide, pixel) replayed on
// pool B with one render as one sample (printReplays), against uniform at equal samples.
//
// Usage: adaptive_oracle SCENE [--resolution 320x240] [--seeds 128] [--spp 16]
//            [--budgets 32,64,128,256] [--max-spp 1024] [--pilot 2] [--out bench-out]
//            [--reference EXR] [--reference-spp 4096] [--threads 0]
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "bench/cpu_time.h"
#include "bench/image_error.h"
#include "bench/oracle_allocation.h"
#include "bench/oracle_pools.h"
#include "bench/oracle_setup.h"
#include "bench/sweep.h"
#include "core/error.h"
#include "gltf/gltf_loader.h"
#include "io/image_output.h"
#include "render/prepared_scene.h"
#include "render/render_setup.h"
#include "render/noise_estimate.h"
#include "render/renderer.h"

namespace fs = std::filesystem;
using namespace tray;

namespace {

struct Setup : OracleSetup {
  int pilot = 2, referenceSpp = 4096;
};

Film renderWith(const PreparedScene& prepared, ImageSize size, const RenderSettings& s,
                int threads) {
  auto integrator = prepared.integrator(s);
  Film film(size.width, size.height);
  RenderOptions opt;
  opt.threads = threads;
  renderImage(*integrator, film, opt);
  return film;
}

/// The replayed threshold rules against uniform at equal samples (trimmed relMSE), with their
/// image means against uniform's at 64 renders.
void printReplays(const std::vector<float>& means, int first, int available, int spp,
                  const Film& ref) {
  const int w = ref.width(), h = ref.height();
  const size_t pixels = size_t(w) * h;
  std::vector<std::pair<double, double>> uniform;
  for (int k : {2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64})
    if (k <= available)
      uniform.emplace_back(double(k) * spp,
                           compareBeauty(imageOf(means, std::vector<int>(pixels, k), first, w, h),
                                         ref).relMseTrimmed);
  std::printf("\nTRay's threshold rules replayed (a step of one render = %d spp, --min-spp %d):"
              "\n\n| decision | threshold | mean spp | trimmed relMSE | uniform at that spp | "
              "gain | bias |\n|---|---|---|---|---|---|---|\n",
              spp, 2 * spp);
  using D = SamplingPasses::Decision;
  const std::pair<const char*, D> decisions[] = {
      {"neighbours", D::kNeighbours}, {"wide", D::kWide}, {"pixel (biased)", D::kPixel}};
  for (const auto& [name, decision] : decisions)
    for (float t : {0.1f, 0.05f, 0.03f, 0.02f, 0.01f}) {
      SamplingPasses passes;
      passes.threshold = t, passes.minSamples = 2, passes.decision = decision;
      const std::vector<int> steps = replay(means, first, available, w, h, passes);
      double mean = 0;
      for (int k : steps) mean += double(k) * spp / double(pixels);
      const ImageError e = compareBeauty(imageOf(means, steps, first, w, h), ref);
      const double u = uniformAt(uniform, mean);
      std::printf("| %s | %.2f | %.1f | %.3e | %.3e | %.3f | %+.2e |\n", name, t, mean,
                  e.relMseTrimmed, u, u / e.relMseTrimmed, e.bias);
    }
}

/// `o.seeds` renders of `o.spp` samples, seeds 1000 on (neither the sweep's 0 nor the
/// reference's): render-major, RGB per pixel.
std::vector<float> renderSeeds(const PreparedScene& prepared, ImageSize size, const Setup& o) {
  const int w = size.width;
  const size_t pixels = size_t(w) * size.height;
  RenderSettings s;
  s.set("integrator", "path"), s.set("sampler", "sobol"), s.set("pixel-sampler", "sequence");
  s.set("spp", o.spp);
  std::vector<float> means(size_t(o.seeds) * pixels * 3);
  for (int j = 0; j < o.seeds; ++j) {
    s.set("seed", 1000 + j);
    const Film f = renderWith(prepared, size, s, o.threads);
    for (size_t p = 0; p < pixels; ++p)
      for (int c = 0; c < 3; ++c)
        means[(size_t(j) * pixels + p) * 3 + c] =
            f.pixel(Film::kBeauty, int(p % w), int(p / w))[c];
  }
  return means;
}

/// The allocations of the header comment against uniform at each budget, as a table.
void printAllocations(const std::vector<float>& means, const Setup& o, const Film& ref) {
  const int w = ref.width(), h = ref.height();
  const size_t pixels = size_t(w) * h;
  const int half = o.seeds / 2, poolB = half, stepsB = o.seeds - half;
  const std::vector<double> aA = relativeVariance(means, pixels, 0, half, o.spp, ref);
  const std::vector<double> aB = relativeVariance(means, pixels, half, o.seeds, o.spp, ref);
  std::vector<double> aPilot = relativeVariance(means, pixels, 0, o.pilot, o.spp, ref);
  const std::vector<double> aPilot3 = boxAverage(aPilot, w, h, 1, true);
  const std::vector<double> aPilot5 = boxAverage(aPilot, w, h, 2, true);
  const std::vector<double> aNeighbours = boxAverage(aA, w, h, 1, false);
  // What an implementable one-shot rule sees: every pixel's first P renders of pool B (kept in
  // its mean), and its count from its neighbours' estimates only.
  const std::vector<double> aKept =
      relativeVariance(means, pixels, half, half + o.pilot, o.spp, ref);
  const std::vector<double> aKept3 = boxAverage(aKept, w, h, 1, false);
  const std::vector<double> aKept5 = boxAverage(aKept, w, h, 2, false);
  std::vector<double> aTrim = aA;  // the 0.1% largest held at one step
  {
    const size_t cut = std::max<size_t>(1, pixels / 1000);
    std::vector<double> sorted = aA;
    std::nth_element(sorted.begin(), sorted.end() - cut, sorted.end());
    const double limit = sorted[sorted.size() - cut];
    for (double& v : aTrim)
      if (v >= limit) v = 0;
  }
  std::printf("unbounded gain mean(a)/mean(sqrt a)^2: pool A %.3f, pool B %.3f\n\n",
              unboundedGain(aA), unboundedGain(aB));
  std::printf("| budget spp | allocation | mean spp | expected relMSE gain (pool B's a) | "
              "relMSE | relMSE gain | trimmed relMSE | trimmed gain |\n|---|---|---|---|---|---|"
              "---|---|\n");
  const double cap = std::min<double>(o.maxSpp, double(stepsB) * o.spp);
  std::stringstream list(o.budgets);
  for (std::string item; std::getline(list, item, ',');) {
    const int budget = std::stoi(item);
    if (budget % o.spp || budget / o.spp > stepsB) continue;
    const std::vector<int> uniformSteps(pixels, budget / o.spp);
    const std::vector<double> uniformN(pixels, double(budget));
    const ImageError u = compareBeauty(imageOf(means, uniformSteps, poolB, w, h), ref);
    const double uExpected = expectedRelMse(aB, uniformN);
    std::printf("| %d | uniform | %d | 1 | %.3e | 1 | %.3e | 1 |\n", budget, budget, u.relMse,
                u.relMseTrimmed);
    struct Rule {
      std::string name;
      const std::vector<double>* a;
      double spent;  // samples thrown away per pixel (a pilot)
      int minSteps;  // steps every pixel takes
    };
    const double pilotSpp = o.pilot * o.spp;
    const std::string pilot = "pilot " + std::to_string(int(pilotSpp)) + " spp";
    const std::string oneShot =
        "one-shot from the neighbours' first " + std::to_string(int(pilotSpp)) + " spp, ";
    for (const Rule& r :
         {Rule{"oracle", &aA, 0, 1}, Rule{"oracle-trim", &aTrim, 0, 1},
          Rule{"oracle of the 8 neighbours", &aNeighbours, 0, 1},
          Rule{pilot, &aPilot, pilotSpp, 1}, Rule{pilot + " 3x3", &aPilot3, pilotSpp, 1},
          Rule{pilot + " 5x5", &aPilot5, pilotSpp, 1}, Rule{oneShot + "3x3", &aKept3, 0, o.pilot},
          Rule{oneShot + "5x5", &aKept5, 0, o.pilot}}) {
      if (budget - r.spent < r.minSteps * o.spp) continue;
      const std::vector<double> n =
          oracleAllocation(*r.a, budget - r.spent, r.minSteps * o.spp, cap);
      const std::vector<int> steps = wholeSteps(n, o.spp, stepsB);
      std::vector<double> kept(pixels);
      double spp = 0;
      for (size_t p = 0; p < pixels; ++p) kept[p] = steps[p] * o.spp, spp += kept[p] / pixels;
      const ImageError e = compareBeauty(imageOf(means, steps, poolB, w, h), ref);
      std::printf("| %d | %s | %.1f | %.3f | %.3e | %.3f | %.3e | %.3f |\n", budget,
                  r.name.c_str(), spp + r.spent, uExpected / expectedRelMse(aB, kept), e.relMse,
                  u.relMse / e.relMse, e.relMseTrimmed, u.relMseTrimmed / e.relMseTrimmed);
    }
  }
}

int run(const Setup& o) {
  const OracleScene loaded = loadOracleScene(o);
  const ImageSize size = loaded.size;
  const PreparedScene prepared(loaded.scene, loaded.camera, size, "embree");
  const int w = size.width, h = size.height;
  fs::create_directories(o.out);
  const std::string stem = fs::path(o.scene).stem().string();
  // The sweep's cached reference, so that one render serves both.
  const std::string refPath = oracleReferencePath(o, size);
  if (!fs::exists(refPath)) {
    std::fprintf(stderr, "adaptive_oracle: rendering the reference to %s\n", refPath.c_str());
    ImageOutputOptions io;
    io.halfFloat = false;
    writeImage(renderWith(prepared, size, referenceSettings("path", o.referenceSpp), o.threads),
               refPath, io);
  }
  const Film ref = readReferenceOfSize(refPath, w, h);

  const double cpu0 = cpuSeconds();
  const std::vector<float> means = renderSeeds(prepared, size, o);
  std::printf("%s, %dx%d: %d renders of %d spp (%.1f CPU s each); pool A (variances) renders "
              "0..%d, pool B (samples) %d..%d\n",
              stem.c_str(), w, h, o.seeds, o.spp, (cpuSeconds() - cpu0) / o.seeds,
              o.seeds / 2 - 1, o.seeds / 2, o.seeds - 1);
  printAllocations(means, o, ref);
  printReplays(means, o.seeds / 2, o.seeds - o.seeds / 2, o.spp, ref);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"adaptive_oracle: the best unbiased per-pixel allocation against uniform"};
  Setup o;
  addOracleOptions(app, o);
  app.add_option("--pilot", o.pilot, "renders of the pilot rules")->capture_default_str();
  addOracleOutputOptions(app, o);
  app.add_option("--reference-spp", o.referenceSpp, "spp of a rendered reference")
      ->capture_default_str();
  return runOracleTool(app, argc, argv, "adaptive_oracle", [&] { return run(o); });
}
