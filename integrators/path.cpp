#include "integrators/path.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <limits>

#include "core/error.h"
#include "core/front_face.h"
#include "core/shading.h"
#include "lights/light_set.h"
#include "materials/bsdf.h"
#include "materials/medium_stack.h"

namespace tray {
namespace {

/// Beer-Lambert transmittance exp(-sigma_a d) per channel (KHR_materials_volume).
Color transmittance(const Color& sigmaA, float d) {
  return {std::exp(-sigmaA.x * d), std::exp(-sigmaA.y * d), std::exp(-sigmaA.z * d)};
}

/// Absorption of the medium beyond a refractive surface: the one in effect once crossed.
Color farSideAbsorption(const MediumStack& media, int id, const Material& m, bool entering) {
  MediumStack far = media;
  far.cross(id, m, entering);
  return far.currentAbsorption();
}

/// The pixel being rendered on this thread, for --debug-nan reports (Li does not know it).
thread_local int tlsPixelX = -1, tlsPixelY = -1;

class PathIntegrator final : public Integrator {
 public:
  explicit PathIntegrator(const RenderContext& ctx)
      : Integrator(ctx),
        maxDepth_(ctx.settings.getInt("max-depth")),
        clampIndirect_(ctx.settings.getFloat("clamp-indirect")),
        debugNan_(ctx.settings.getBool("debug-nan")),
        absorbingMedia_(std::any_of(ctx.scene.materials.begin(), ctx.scene.materials.end(),
                                    [](const Material& m) { return !isBlack(m.layers.absorption()); })),
        lights_(ctx.scene, lightSamplerKind(ctx.settings.getString("light-sampler"))),
        materials_(ctx.scene, ctx.camera, ctx.settings.getInt("spp")) {}

  uint32_t accumulate(int x, int y, int begin, int end, PixelSums& sums, PrimaryHit& first,
                      RayStats& stats, IdCoverage* coverage, AovSums* aovSums) const override {
    tlsPixelX = x, tlsPixelY = y;
    return Integrator::accumulate(x, y, begin, end, sums, first, stats, coverage, aovSums);
  }
  bool splitsLightPaths() const override { return true; }

  Color Li(const Ray& cameraRay, Sampler& sampler, RayStats& stats,
           PrimaryHit* primary) const override;

 private:
  /// Prints where a non-finite value appeared (first few only); the base class then discards
  /// and counts the sample.
  void reportNan(const char* what, int depth) const {
    if (!debugNan_ || nanReports_.fetch_add(1) >= kMaxNanReports) return;
    std::fprintf(stderr, "debug-nan: pixel (%d, %d), depth %d: non-finite %s\n", tlsPixelX,
                 tlsPixelY, depth, what);
  }
  static constexpr int kMaxNanReports = 10;
  /// Mitsuba's default: Russian roulette from the fifth segment on.
  static constexpr int kRouletteDepth = 5;
  /// Passes through false interfaces of nested dielectrics before giving up on a path.
  static constexpr int kMaxNullCrossings = 64;
  int maxDepth_;
  float clampIndirect_;
  bool debugNan_;
  bool absorbingMedia_;  ///< some material absorbs (KHR_materials_volume): NEE looks it up
  LightSet lights_;
  MaterialEvaluator materials_;
  mutable std::atomic<int> nanReports_{0};
};

Color PathIntegrator::Li(const Ray& cameraRay, Sampler& sampler, RayStats& stats,
                         PrimaryHit* primary) const {
  const Scene& scene = ctx_.scene;
  Color L(0.0f), beta(1.0f);
  if (maxDepth_ == 0) return L;
  Ray ray = cameraRay;
  int depth = 1;  // segments so far, counting the one being traced
  int nullCrossings = 0;
  bool specular = true;  // the last scattering was a delta lobe (or the camera): no MIS
  float prevPdf = 0;     // BSDF pdf of the last scattering, for MIS against light sampling
  LightSampleContext prev;  // the last scattering point, as light sampling saw it
  float etaFactor = 1;  // undoes the 1/eta^2 radiance scaling for Russian roulette
  MediumStack media;
  // Firefly clamping (--clamp-indirect): light that reached the camera path after scattering
  // off a diffuse or glossy vertex earlier than the one gathering it (caustics, interreflection)
  // is "indirect". Each such contribution is scaled down, keeping its hue, so that its largest
  // component is at most clampIndirect_: biased (energy is lost) but bounded per sample, the
  // "clamp indirect" of Cycles and Arnold. Direct light at the first non-delta vertex, and
  // emitters seen directly or through mirrors and glass, are never clamped.
  bool indirectNee = false;       // a non-delta vertex precedes the current one
  bool indirectEmission = false;  // ... precedes the vertex the traced ray left from
  auto add = [&](Color c, const char* what, bool indirect) {
    if (!isFinite(c)) reportNan(what, depth);
    if (clampIndirect_ > 0 && indirect) {  // the constant first: a predictable branch
      const float peak = maxComponent(c);
      if (peak > clampIndirect_) c *= clampIndirect_ / peak;
    }
    L += c;
    return c;
  };
  // Light-path AOVs (core/light_paths.h), only when asked for: each contribution also goes to
  // the category of its path.
  LightPathSplitter paths(primary ? primary->lightPaths : nullptr);

  for (;;) {
    Hit hit;
    // KHR_materials_volume: the segment crosses the medium in effect, which absorbs.
    const Color sigmaA = media.currentAbsorption();
    const bool absorbing = !isBlack(sigmaA);
    if (!ctx_.accel.intersect(ray, hit)) {
      if (absorbing) break;  // lost inside an open absorbing mesh: transmittance exp(-inf) = 0
      // Escaped: the infinite lights' radiance, weighted against their light-sampling pdfs.
      for (int i : lights_.infinite()) {
        const Vec3 dir = normalize(ray.d);
        const Color Le = lights_.light(size_t(i)).Le(dir);
        if (isBlack(Le)) continue;
        float w = specular ? 1.0f : powerHeuristic(prevPdf, lights_.pdf(i, prev, dir, {}, {}));
        paths.addFound(add(beta * Le * w, "environment", indirectEmission), true);
      }
      break;
    }
    if (absorbing) {
      beta *= transmittance(sigmaA, hit.t * length(ray.d));
      if (isBlack(beta)) break;
    }
    SurfacePoint s = scene.surface(ray, hit);
    const Material& m = scene.material(s.material);
    const Vec3 wo = -normalize(ray.d);

    // Nested dielectrics: a surface of a medium that is not in effect is passed straight by.
    // A metallicRoughnessTexture can lower metallic below a factor of 1 (glTF's default factor,
    // which the Khronos transmission samples keep): such a surface may transmit too.
    const bool refractive =
        m.transmission > 0 && (m.metallic < 1 || m.metallicRoughnessTexture.valid());
    float eta = m.ior / media.currentIor();
    if (refractive) {
      MediumStack::Interface iface = media.interface(s.material, m, s.frontFace);
      if (!iface.real) {
        media.cross(s.material, m, s.frontFace);
        if (++nullCrossings > kMaxNullCrossings) break;
        ray = spawnRay(s.p, s.ng, ray.d);
        ++stats.secondaryRays;
        continue;
      }
      eta = iface.etaT / iface.etaI;
    }
    // Textures are evaluated only at surfaces that scatter or emit (not at null interfaces).
    ShadingMaterial sm = materials_.evaluate(hit, s);
    // The clearcoat and sheen are on the outside of a transmissive solid: not seen from within.
    if (refractive && !s.frontFace) sm.clearcoat = 0, sm.sheenColor = Color(0.0f);
    if (primary && !primary->hit) {
      primary->hit = true;
      primary->depth = length(s.p - cameraRay.o);
      primary->position = s.p;
      primary->normal = sm.n;
      primary->albedo = sm.baseColor;
      primary->objectId = scene.primitives[s.primitive].objectId;
      primary->materialId = s.material;
    }
    // KHR_materials_unlit: the base colour leaves the surface as is and nothing scatters, as
    // from an emitter that is not in the light set (docs/scene-format.md, "Unlit").
    if (sm.unlit) {
      paths.addFound(add(beta * sm.baseColor, "unlit surface", indirectEmission), false);
      break;
    }

    // Emission found by BSDF sampling (or seen directly), MIS-weighted against the chance
    // that light sampling would have picked the same point.
    if (!isBlack(sm.emissive) && emitsToward(s.front, -ray.d, m.doubleSided)) {
      float w = 1.0f;
      int light = lights_.lightAt(hit.primitive, hit.triangle);
      if (!specular && light >= 0)
        w = powerHeuristic(prevPdf, lights_.pdf(light, prev, -wo, s.p, s.ng));
      paths.addFound(add(beta * sm.emissive * w, "emission", indirectEmission), false);
    }
    if (depth + 1 > maxDepth_) break;

    // Shade on the side the ray arrived from.
    const Vec3 n = s.frontFace ? sm.n : -sm.n;
    const Bsdf bsdf(sm, Frame::fromNormal(n), eta);

    // What light sampling knows of the receiver; BSDF sampling's MIS weights use the same.
    // A reflecting BSDF sees only light above n unless wo lies below it (shading normals) or
    // a clearcoat brings a normal of its own.
    const LightSampleContext here{s.p, n, bsdf.transmits(),
                                  bsdf.transmits() || !(dot(wo, n) > 0) || sm.clearcoat > 0};
    // Next-event estimation: one light sample, MIS-weighted against BSDF sampling.
    if (bsdf.hasNonDelta() && !lights_.empty()) {
      // The light choice and the point on it as one 3D sample (stratified jointly by Sobol').
      const Vec3 u = sampler.next3D();
      LightSample ls = lights_.sample(here, u.x, {u.y, u.z});
      if (ls.valid() && !isBlack(ls.L)) {
        float bsdfPdf;
        Color f = bsdf.eval(wo, ls.wi, bsdfPdf) * std::fabs(dot(ls.wi, n));
        if (!isBlack(f)) {
          Ray shadow = ls.infinite ? spawnRay(s.p, s.ng, ls.wi) : spawnRayTo(s.p, s.ng, ls.p);
          ++stats.shadowRays;
          if (!ctx_.accel.occluded(shadow)) {
            float w = ls.delta ? 1.0f : powerHeuristic(ls.pdf, bsdfPdf);
            // An unoccluded shadow ray crossed one medium: the one on its side of s.
            const Color sigma = absorbingMedia_ && refractive && dot(ls.wi, n) < 0
                                    ? farSideAbsorption(media, s.material, m, s.frontFace)
                                    : sigmaA;
            if (!isBlack(sigma))
              f *= ls.infinite ? Color(0.0f) : transmittance(sigma, length(ls.p - s.p));
            const Color c = add(beta * f * ls.L * (w / ls.pdf), "light sample", indirectNee);
            if (paths.active())
              paths.addLightSample(c, paths.atFirstVertex() ? bsdf.evalLobes(wo, ls.wi)
                                                            : LobeSplit{});
          }
        }
      }
    }

    // BSDF sampling continues the path.
    const Vec3 u = sampler.next3D();  // the lobe choice, then the direction
    BsdfSample bs = bsdf.sample(wo, u.x, {u.y, u.z});
    if (!bs.valid()) break;
    beta *= bs.f * (std::fabs(dot(bs.wi, n)) / bs.pdf);
    if (!isFinite(beta)) {
      reportNan("path throughput", depth);
      return Color(std::numeric_limits<float>::quiet_NaN());  // counted and discarded upstream
    }
    if (isBlack(beta)) break;
    specular = bs.delta;
    indirectEmission = indirectNee;
    indirectNee = indirectNee || !bs.delta;
    prevPdf = bs.pdf;
    prev = here;
    if (bs.transmission && refractive) {
      media.cross(s.material, m, s.frontFace);
      etaFactor /= bs.etaScale;
    }
    if (paths.active())
      paths.scattered(!paths.atFirstVertex() ? LobeSplit{}
                      : bs.delta             ? LightPathSplitter::deltaLobe(bs.transmission)
                                             : bsdf.evalLobes(wo, bs.wi));
    ray = spawnRay(s.p, s.ng, bs.wi);
    ++stats.secondaryRays;
    ++depth;

    // Russian roulette (Arvo & Kirk 1990) with Mitsuba's survival probability.
    if (depth > kRouletteDepth) {
      float q = std::min(maxComponent(beta) * etaFactor, 0.95f);
      if (!(sampler.next1D() < q)) break;
      beta /= q;
    }
  }
  return L;
}

}  // namespace

const std::vector<OptionSpec>& pathOptions() {
  static const std::vector<OptionSpec> specs = {
      intOption("max-depth", 8, 0, 1000,
                "maximum path length in segments (1: emitters seen directly; 2: direct light)"),
      floatOption("clamp-indirect", 0.0f, 0.0f, std::numeric_limits<float>::infinity(),
                  "clamp each indirect contribution to this value (fireflies; biased; 0 = off)"),
      // Prints only: the pixels are the same with or without it.
      diagnostic(flagOption("debug-nan", "print where NaN/Inf samples arise")),
      choiceOption("light-sampler", "bvh", {"bvh", "power"},
                   "how next-event estimation picks a light: bvh (by its estimated "
                   "contribution at the shading point) or power (in proportion to power)"),
  };
  return specs;
}

std::unique_ptr<Integrator> makePath(const RenderContext& ctx) {
  return std::make_unique<PathIntegrator>(declaring(ctx, pathOptions()));
}

}  // namespace tray
