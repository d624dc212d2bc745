#include "bench/sweep.h"

#include <filesystem>

#include "integrators/registry.h"

namespace tray {
namespace {

bool registered(const std::string& name) {
  for (const auto& e : integratorRegistry())
    if (name == e.name) return true;
  return false;
}

}  // namespace

std::vector<SweepConfig> standardSweep(const std::vector<std::string>& accels,
                                       const std::vector<int>& threads, int maxSpp) {
  std::vector<SweepConfig> base;
  auto add = [&](std::string method, std::string setting, RenderSettings s) {
    base.push_back({std::move(method), std::move(setting), std::move(s)});
  };
  // Whitted: anti-aliasing strategies at growing cost.
  RenderSettings w;
  w.set("integrator", "whitted");
  w.set("pixel-sampler", "center");
  add("whitted center", "spp=1", w);
  for (int n : {2, 4, 8}) {
    if (n * n > maxSpp) break;
    w.set("pixel-sampler", "grid"), w.set("spp", n * n);
    add("whitted grid", "spp=" + std::to_string(n * n), w);
    w.set("pixel-sampler", "jitter");
    add("whitted jitter", "spp=" + std::to_string(n * n), w);
  }
  if (registered("adaptive")) {
    RenderSettings a;
    a.set("integrator", "adaptive");
    a.set("inner", "whitted");
    for (float t : {0.2f, 0.1f, 0.05f, 0.02f}) {
      a.set("aa-threshold", t);
      add("whitted adaptive", "threshold=" + std::to_string(t).substr(0, 4), a);
    }
  }
  // Path tracing: error against samples.
  if (registered("path")) {
    RenderSettings p;
    p.set("integrator", "path");
    p.set("pixel-sampler", "jitter");
    p.set("sampler", "independent");
    for (int spp = 1; spp <= maxSpp; spp *= 4) {
      p.set("spp", spp);
      add("path", "spp=" + std::to_string(spp), p);
    }
    // The same estimator on Owen-scrambled Sobol' numbers, camera rays at the sequence's own
    // points (TRay's default at power-of-two spp): equal error at fewer samples.
    p.set("sampler", "sobol");
    p.set("pixel-sampler", "sequence");
    for (int spp = 1; spp <= maxSpp; spp *= 4) {
      p.set("spp", spp);
      add("path sobol", "spp=" + std::to_string(spp), p);
    }
    // Noise-driven adaptive sampling (docs/adaptive-sampling.md) of the same estimator, at most
    // the largest spp: the threshold is the setting that varies.
    // "even" (equal error, the rule of Cycles' threshold) beside the default "mse".
    p.set("spp", maxSpp);
    for (const char* rule : {"mse", "even"}) {
      p.set("noise-rule", std::string(rule));
      for (const char* t : {"0.1", "0.05", "0.03", "0.02", "0.01"}) {
        p.set("noise-threshold", std::stof(t));
        add(std::string("path sobol adaptive") + (rule == std::string("mse") ? "" : " even"),
            std::string("threshold=") + t, p);
      }
    }
    // The pixel's own error deciding too (--noise-decision pixel: Cycles' way, biased).
    p.set("noise-rule", std::string("mse"));
    p.set("noise-decision", std::string("pixel"));
    for (const char* t : {"0.1", "0.05", "0.03", "0.02", "0.01"}) {
      p.set("noise-threshold", std::stof(t));
      add("path sobol adaptive pixel", std::string("threshold=") + t, p);
    }
    // The other decisions from neighbours' errors: their largest (--noise-decision max), and
    // the 8 neighbours' mean (neighbours: the default before wide, dark at high thresholds).
    // "path sobol adaptive" above is the default (wide).
    for (const char* decision : {"max", "neighbours"}) {
      p.set("noise-decision", std::string(decision));
      for (const char* t : {"0.1", "0.05", "0.03", "0.02", "0.01"}) {
        p.set("noise-threshold", std::stof(t));
        add(std::string("path sobol adaptive ") + decision, std::string("threshold=") + t, p);
      }
    }
    // The error in radiance units (--noise-metric absolute: the rule then aims at RMSE).
    p.set("noise-decision", std::string("wide"));
    p.set("noise-metric", std::string("absolute"));
    for (const char* t : {"0.02", "0.01", "0.007", "0.005", "0.003"}) {
      p.set("noise-threshold", std::stof(t));
      add("path sobol adaptive absolute", std::string("threshold=") + t, p);
    }
  }
  // Every method on every accelerator and thread count: separate lines.
  std::vector<SweepConfig> out;
  for (const auto& accel : accels)
    for (int t : threads)
      for (SweepConfig c : base) {
        if (accels.size() > 1) c.method += " [" + accel + "]";
        if (threads.size() > 1) c.method += " [" + std::to_string(t) + "t]";
        c.accel = accel;
        c.threads = t;
        out.push_back(std::move(c));
      }
  return out;
}

RenderSettings referenceSettings(const std::string& integrator, int referenceSpp) {
  RenderSettings s;
  if (integrator == "path") {
    s.set("integrator", "path");
    s.set("pixel-sampler", "jitter");
    s.set("spp", referenceSpp);
  } else {
    // Whitted-family methods converge to the 32x32 grid.
    s.set("integrator", "whitted");
    s.set("pixel-sampler", "grid");
    s.set("spp", 32 * 32);
  }
  s.set("seed", 0x5eed);  // a seed no sweep run uses, so reference noise is independent
  return s;
}

std::string referencePath(const std::string& outDir, const std::string& scenePath,
                          const std::string& family, int width, int height) {
  const std::string stem = std::filesystem::path(scenePath).stem().string();
  return outDir + "/reference-" + stem + "-" + family + "-" + std::to_string(width) + "x" +
         std::to_string(height) + ".exr";
}

}  // namespace tray
