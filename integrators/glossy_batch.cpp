// Highway's dynamic dispatch, as integrators/matte_batch.cpp: compiled once per x86 target,
// with -ffp-contract=off (as the whole project). Each lane runs PathEstimator::step's second
// half for Bsdf's metal and plastic mixture, from the same text the scalar code runs (the
// *_lanes.h files, included by integrators/shading_simd-inl.h), so the bits are the same:
// ggxMixture's weights and mixtureProbabilities at wo, the light sample and mixtureEvalPdf
// toward it, powerHeuristic and the shadow ray; mixtureSample, the throughput and the next ray.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "integrators/glossy_batch.cpp"
#include "integrators/glossy_batch.h"

#include "core/simd_lanes.h"
#include "hwy/foreach_target.h"  // IWYU pragma: keep
#include "hwy/highway.h"
// After highway.h, once per target: the lane types and the stages' shared plumbing.
#include "integrators/shading_simd-inl.h"

HWY_BEFORE_NAMESPACE();
namespace tray {
namespace HWY_NAMESPACE {

#if HWY_TARGET == HWY_SCALAR
// MatteBatch::useful() is false without a SIMD target: never called.
void GlossyVertices(const EmitterTables&, ShadingLanes&) {}
#else

/// The mixture of a vector of vertices, in their shading frames, computed once per vertex:
/// what its light sample and its BSDF sample both read.
struct Vertices {
  FrameOf<V3> frame;
  V3 wo;  ///< local
  FloatVec eta;  ///< the coat's relative IOR
  GgxMixtureOf<V3> mixture;
  MixtureProbabilitiesOf<FloatVec> probabilities;
  explicit Vertices(const Fields& f)
      : frame(FrameOf<V3>::fromNormal(f.load(f.m.n))),
        wo(frame.toLocal(f.load(f.m.wo))),
        eta(f.load(f.m.eta)),
        mixture(ggxMixture(f.load(f.m.metallic), FloatVec(0.0f), f.load(f.m.roughness),
                           f.load(f.m.albedo))),
        probabilities(mixtureProbabilities(mixture, coatFresnelOf(mixture.coat, wo.z, eta))) {}
  /// The coat's exact dielectric Fresnel at a microfacet cosine (no KHR_materials_specular
  /// tint here: Bsdf::isGgxMixture).
  auto coatFresnel() const {
    return [eta = eta](FloatVec cosOM) {
      const FloatVec fr = fresnelDielectric(absOf(cosOM), eta);
      return V3{fr, fr, fr};
    };
  }
};

/// Next-event estimation of one vector of vertices: the chosen light's sample, the mixture
/// toward it (Bsdf::eval with its pdf) times the cosine, powerHeuristic and the shadow ray.
/// Out of line, as ScatterSample: inlined into GlossyVertices, clang's sanitizer build of this
/// file (tools/fuzz.sh) took 6.5 minutes and 4.6 GB.
template <bool kEnvironment>
HWY_NOINLINE void LightSample(const Fields& f, const EmitterTables& tables, const Vertices& v) {
  const V3 p = f.load(f.m.p), ng = f.load(f.m.ng);
  const V3& n = v.frame.n;
  const ChosenLightSample ls = SampleChosenLight<kEnvironment>(f, tables, p, n);
  FloatVec bsdfPdf, ggxPdf;
  const V3 e = mixtureEvalPdf(v.mixture, v.probabilities, v.wo, v.frame.toLocal(ls.wi),
                              v.coatFresnel(), NoGlass(), bsdfPdf, ggxPdf);
  StoreLightSample(f, ls, e * absOf(dot(ls.wi, n)), bsdfPdf, p, ng);
}

/// BSDF sampling of one vector of vertices: Bsdf::sampleLocal's mixture (the lobe choice, GGX
/// visible normals, a mirror or the cosine lobe, the mixture's value and pdf there), then to
/// world space.
HWY_NOINLINE void ScatterSample(const Fields& f, const Vertices& v) {
  const MixtureSampleOf<V3> s =
      mixtureSample(v.mixture, v.probabilities, v.wo, f.load(f.m.lobeDraw), f.load(f.m.bsdfDraw),
                    v.coatFresnel(), NoGlass());
  StoreNextRay(f, s.f, v.frame.toWorld(s.wi), v.frame.n, s.pdf);
  f.store(f.m.deltaSample, maskBits(s.delta));
}

void GlossyVertices(const EmitterTables& tables, ShadingLanes& lanes) {
  const size_t n = hn::Lanes(DF());
  // Whole vectors: the inputs are padded (ShadingLanes::padInputs), and the outputs have room.
  for (size_t q = 0; q < lanes.count; q += n) {
    const Fields f{lanes, q};
    const Vertices v(f);
    if (noneOf(EnvironmentLanes(f)))
      LightSample<false>(f, tables, v);
    else
      LightSample<true>(f, tables, v);
    ScatterSample(f, v);
  }
}

#endif  // HWY_TARGET != HWY_SCALAR
}  // namespace HWY_NAMESPACE
}  // namespace tray
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace tray {
HWY_EXPORT(GlossyVertices);

GlossyBatch::GlossyBatch(const MatteBatch& lights) : lights_(lights) {}

void GlossyBatch::compute(ShadingLanes& lanes) const {
  if (lanes.count == 0) return;
  lanes.padInputs();
  HWY_DYNAMIC_DISPATCH(GlossyVertices)(lights_.tables(), lanes);
}

}  // namespace tray
#endif  // HWY_ONCE
