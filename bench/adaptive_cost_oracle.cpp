// adaptive_cost_oracle: how much weighing each pixel's cost per sample can add to the
// unbiased oracle allocation at equal cost (issue 37; docs/bench/adaptive-cost-2026-12-07.md).
//
// As bench/adaptive_oracle (its pools, its reference, its model caveat), but every pixel of
// every render is traced on its own by `path-scalar` (the same pixels as `path`), so that the
// rays it traced and the CPU time it took are known per pixel and render. Pool A (the first
// half of the renders) gives each pixel's relative variance a_i and its cost per sample c_i
// (rays, or CPU seconds); pool B is what the allocations spend, and what they spend is
// counted from pool B's own costs. Per budget (uniform's spp) and per currency (rays traced,
// CPU seconds), at uniform's cost in that currency:
//   oracle             n_i proportional to sqrt(a_i) (cost-blind, adaptive_oracle's)
//   cost-aware         n_i proportional to sqrt(a_i / c_i) (bench/oracle_allocation.h)
//   ... of the 8 neighbours   the same from the 8 neighbours' a and c (the pixel left out)
//   cost-aware by rays (CPU seconds only)   weighed by rays, spending CPU seconds: what a
//                      renderer that counts rays (deterministic) can do at equal time
// each with its trimmed relMSE gain over uniform at equal cost (uniform's error interpolated
// log-log at the allocation's cost) and the expected gain (pool B's a and c, closed form).
// (Commit 2b12d4d also replayed TRay's rules with a --noise-cost rays stopping rule, since
// reverted: docs/bench/adaptive-cost-2026-12-07.md.)
//
// Usage: adaptive_cost_oracle SCENE [--resolution 320x240] [--seeds 128] [--spp 16]
//            [--budgets 32,64,128,256] [--max-spp 1024] [--out bench-out] [--reference EXR]
//            [--threads 0]
#include <CLI/CLI.hpp>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <time.h>

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
#include "render/prepared_scene.h"
#include "render/render_setup.h"

namespace fs = std::filesystem;
using namespace tray;

namespace {

using Setup = OracleSetup;

/// The renders: means as bench/oracle_pools.h lays them out, and beside each pixel of each
/// render the rays it traced and the CPU seconds it took (render-major).
struct Pools {
  std::vector<float> means, rays, seconds;
};

double threadSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

Pools renderPools(const PreparedScene& prepared, const Setup& o) {
  const int w = prepared.width(), h = prepared.height();
  const size_t pixels = size_t(w) * h;
  Pools pools;
  pools.means.resize(size_t(o.seeds) * pixels * 3);
  pools.rays.resize(size_t(o.seeds) * pixels);
  pools.seconds.resize(pools.rays.size());
  RenderSettings s;
  s.set("integrator", "path-scalar"), s.set("sampler", "sobol");
  s.set("pixel-sampler", "sequence"), s.set("spp", o.spp);
  tbb::task_arena arena(o.threads > 0 ? o.threads : tbb::task_arena::automatic);
  for (int j = 0; j < o.seeds; ++j) {
    s.set("seed", 1000 + j);  // adaptive_oracle's seeds: the same renders
    const auto integrator = prepared.integrator(s);
    arena.execute([&] {
      tbb::parallel_for(0, h, [&](int y) {
        for (int x = 0; x < w; ++x) {
          PixelSums sums;
          PrimaryHit first;
          RayStats stats;
          const double t0 = threadSeconds();
          integrator->accumulate(x, y, 0, o.spp, sums, first, stats);
          const size_t q = size_t(j) * pixels + size_t(y) * w + x;
          pools.seconds[q] = float(threadSeconds() - t0);
          pools.rays[q] = float(stats.total());
          const Color L = sums.radiance();
          for (int c = 0; c < 3; ++c) pools.means[q * 3 + c] = L[c];
        }
      });
    });
  }
  return pools;
}

/// Each pixel's mean cost of one sample over renders [first, last) of `cost`.
std::vector<double> costPerSample(const std::vector<float>& cost, size_t pixels, int first,
                                  int last, int spp) {
  std::vector<double> c(pixels, 0.0);
  for (int j = first; j < last; ++j)
    for (size_t p = 0; p < pixels; ++p) c[p] += cost[size_t(j) * pixels + p];
  for (double& v : c) v /= double(last - first) * spp;
  return c;
}

/// What the image whose pixel p averages renders first .. first + steps[p] - 1 cost.
double spent(const std::vector<float>& cost, const std::vector<int>& steps, int first) {
  const size_t pixels = steps.size();
  double s = 0;
  for (size_t p = 0; p < pixels; ++p)
    for (int j = first; j < first + steps[p]; ++j) s += cost[size_t(j) * pixels + p];
  return s;
}

/// Uniform's (cost, trimmed relMSE) at whole numbers of pool B's renders: the curve the
/// allocations are compared with at equal cost.
std::vector<std::pair<double, double>> uniformCurve(const Pools& pools,
                                                    const std::vector<float>& cost, int first,
                                                    int available, const Film& ref) {
  const int w = ref.width(), h = ref.height();
  std::vector<std::pair<double, double>> curve;
  for (int k : {1, 2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64})
    if (k <= available) {
      const std::vector<int> steps(size_t(w) * h, k);
      curve.emplace_back(spent(cost, steps, first),
                         compareBeauty(imageOf(pools.means, steps, first, w, h), ref)
                             .relMseTrimmed);
    }
  return curve;
}

struct Currency {
  const char* name;
  const std::vector<float>* cost;
};

/// The allocations of the header comment against uniform at each budget and currency.
void printAllocations(const Pools& pools, const Setup& o, const Film& ref) {
  const int w = ref.width(), h = ref.height();
  const size_t pixels = size_t(w) * h;
  const int half = o.seeds / 2, stepsB = o.seeds - half;
  const std::vector<double> aA = relativeVariance(pools.means, pixels, 0, half, o.spp, ref);
  const std::vector<double> aB = relativeVariance(pools.means, pixels, half, o.seeds, o.spp, ref);
  const std::vector<double> aNeighbours = boxAverage(aA, w, h, 1, false);
  const std::vector<double> raysA = costPerSample(pools.rays, pixels, 0, half, o.spp);
  const double cap = std::min<double>(o.maxSpp, double(stepsB) * o.spp);
  for (const Currency& cur : {Currency{"rays", &pools.rays}, Currency{"CPU s", &pools.seconds}}) {
    const std::vector<double> cA = costPerSample(*cur.cost, pixels, 0, half, o.spp);
    const std::vector<double> cB = costPerSample(*cur.cost, pixels, half, o.seeds, o.spp);
    const std::vector<double> cNeighbours = boxAverage(cA, w, h, 1, false);
    double meanC = 0;
    for (double c : cA) meanC += c / double(pixels);
    std::printf("\n## At equal %s (pool A: %.4g per sample on average)\n\nunbounded gain over "
                "uniform at equal %s: cost-blind %.3f, cost-aware %.3f (pool A), %.3f, %.3f "
                "(pool B)\n\n| budget spp | allocation | mean spp | %s / uniform's | expected "
                "gain (pool B) | trimmed relMSE | trimmed gain at equal %s |\n|---|---|---|---|"
                "---|---|---|\n",
                cur.name, meanC, cur.name, unboundedGainAtEqualCost(aA, cA, true),
                unboundedGainAtEqualCost(aA, cA), unboundedGainAtEqualCost(aB, cB, true),
                unboundedGainAtEqualCost(aB, cB), cur.name, cur.name);
    const auto curve = uniformCurve(pools, *cur.cost, half, stepsB, ref);
    std::stringstream list(o.budgets);
    for (std::string item; std::getline(list, item, ',');) {
      const int budget = std::stoi(item);
      if (budget % o.spp || budget / o.spp > stepsB) continue;
      const std::vector<int> uniformSteps(pixels, budget / o.spp);
      const double uSpent = spent(*cur.cost, uniformSteps, half);
      std::printf("| %d | uniform | %d | 1 | 1 | %.3e | 1 |\n", budget, budget,
                  uniformAt(curve, uSpent));
      struct Rule {
        std::string name;
        std::vector<double> weight;
      };
      auto root = [](const std::vector<double>& a, const std::vector<double>* c) {
        std::vector<double> r(a.size());
        for (size_t i = 0; i < a.size(); ++i) r[i] = std::sqrt(a[i] / (c ? (*c)[i] : 1.0));
        return r;
      };
      std::vector<Rule> rules{{"oracle", root(aA, nullptr)},
                              {"cost-aware", root(aA, &cA)},
                              {"oracle of the 8 neighbours", root(aNeighbours, nullptr)},
                              {"cost-aware of the 8 neighbours", root(aNeighbours, &cNeighbours)}};
      if (cur.cost != &pools.rays) rules.push_back({"cost-aware by rays", root(aA, &raysA)});
      for (const Rule& r : rules) {
        const std::vector<double> n = weightedAllocation(r.weight, cA, budget * meanC, o.spp, cap);
        const std::vector<int> steps = wholeSteps(n, o.spp, stepsB);
        std::vector<double> kept(pixels);
        double spp = 0;
        for (size_t p = 0; p < pixels; ++p) kept[p] = steps[p] * o.spp, spp += kept[p] / pixels;
        const double cost = spent(*cur.cost, steps, half);
        const double e = compareBeauty(imageOf(pools.means, steps, half, w, h), ref).relMseTrimmed;
        std::printf("| %d | %s | %.1f | %.3f | %.3f | %.3e | %.3f |\n", budget, r.name.c_str(), spp,
                    cost / uSpent, gainAtEqualCost(aB, cB, kept), e, uniformAt(curve, cost) / e);
      }
    }
  }
}

int run(const Setup& o) {
  const OracleScene loaded = loadOracleScene(o);
  const ImageSize size = loaded.size;
  const PreparedScene prepared(loaded.scene, loaded.camera, size, "embree");
  // The sweep's cached reference (adaptive_oracle renders it when missing).
  const Film ref = readReferenceOfSize(oracleReferencePath(o, size), size.width, size.height);
  const double cpu0 = cpuSeconds();
  const Pools pools = renderPools(prepared, o);
  std::printf("%s, %dx%d: %d renders of %d spp, each pixel on its own by path-scalar (%.1f CPU s "
              "each); pool A (variances, costs) renders 0..%d, pool B (samples) %d..%d\n",
              fs::path(o.scene).stem().string().c_str(), size.width, size.height, o.seeds, o.spp,
              (cpuSeconds() - cpu0) / o.seeds, o.seeds / 2 - 1, o.seeds / 2, o.seeds - 1);
  printAllocations(pools, o, ref);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"adaptive_cost_oracle: the cost-aware unbiased oracle against the cost-blind one"};
  Setup o;
  addOracleOptions(app, o);
  addOracleOutputOptions(app, o);
  return runOracleTool(app, argc, argv, "adaptive_cost_oracle", [&] { return run(o); });
}
