#include "integrators/whitted.h"

#include "core/camera_culling.h"
#include "lights/environment_irradiance.h"
#include "lights/light_set.h"
#include "materials/fresnel.h"
#include "textures/alpha.h"
#include "textures/shading.h"

namespace tray {

Color phongDirect(const PhongParams& p, const Vec3& n, const Vec3& wo, const Vec3& wi,
                  const Color& irradiance) {
  float cosI = dot(n, wi);
  if (cosI <= 0) return Color(0.0f);
  Color f = p.diffuse * (1.0f / kPi);
  if (!isBlack(p.specular)) {
    Vec3 r = reflect(-wi, n);
    float cosR = std::max(0.0f, dot(r, wo));
    f += p.specular * ((p.shininess + 2.0f) / (2.0f * kPi) * std::pow(cosR, p.shininess));
  }
  return f * irradiance * cosI;
}

namespace {

class WhittedIntegrator final : public Integrator {
 public:
  explicit WhittedIntegrator(const RenderContext& ctx)
      : Integrator(ctx),
        maxDepth_(ctx.settings.getInt("max-depth")),
        lights_(ctx.scene, LightSamplerKind::kPower),  // only its lists: nothing is chosen
        materials_(ctx.scene, ctx.camera, ctx.settings.getInt("spp")) {
    for (const Material& m : ctx.scene.materials) hasBlend_ |= m.alphaMode == AlphaMode::kBlend;
    // An environment map lights diffuse surfaces by its irradiance; a constant background is
    // only what escaping rays see (TRAY_environment's `ambient` is Whitted's light there).
    for (int i : lights_.infinite())
      if (i != lights_.constantEnvironment()) environment_.emplace_back(lights_.light(size_t(i)));
  }

  Color Li(const Ray& ray, Sampler&, RayStats& stats, PrimaryHit* primary) const override {
    return trace(ray, 0, stats, primary);
  }

 private:
  /// alphaMode BLEND surfaces are hits here (BlendRays::kHit), blended straight: alpha x the
  /// surface + (1 - alpha) x what the ray finds behind it, passing on without a bounce.
  Color trace(const Ray& ray, int depth, RayStats& stats, PrimaryHit* primary,
              int crossings = 0) const {
    Ray r = ray;
    r.blend = BlendRays::kHit;
    Hit hit;
    // The camera's ray passes single-sided back faces (core/camera_culling.h).
    const bool found = depth == 0 && crossings == 0
                           ? intersectCameraRay(ctx_.accel, ctx_.scene, r, hit)
                           : ctx_.accel.intersect(r, hit);
    if (!found) return background(ray.d);
    Color L = shade(r, hit, depth, stats, primary);
    if (!hasBlend_) return L;
    const float alpha = coverage(ctx_.scene, hit);
    if (alpha >= 1 || crossings >= kMaxBlendCrossings) return L;
    const SurfacePoint s = ctx_.scene.surface(r, hit);
    ++stats.secondaryRays;
    return alpha * L + (1 - alpha) * trace(spawnRay(s.p, s.ng, ray.d, s.time), depth, stats,
                                           nullptr, crossings + 1);
  }

  /// Fraction of light that reaches the end of a shadow ray: 0 or 1, or through BLEND surfaces
  /// the product of their (1 - alpha).
  float transmittance(const Ray& shadow) const {
    if (!hasBlend_) return ctx_.accel.occluded(shadow) ? 0.0f : 1.0f;
    Ray r = shadow;
    r.blend = BlendRays::kHit;
    float T = 1.0f;
    for (int k = 0; k <= kMaxBlendCrossings; ++k) {
      Hit hit;
      if (!ctx_.accel.intersect(r, hit)) return T;
      const float alpha = coverage(ctx_.scene, hit);
      if (alpha >= 1 || k == kMaxBlendCrossings) return 0.0f;
      T *= 1 - alpha;
      // Continue with the same direction and what is left of the parameter range.
      const SurfacePoint s = ctx_.scene.surface(r, hit);
      const float left = r.tmax - hit.t;
      r = spawnRay(s.p, s.ng, r.d, s.time);
      r.blend = BlendRays::kHit;
      r.tmax = left;
    }
    return T;
  }

  Color shade(const Ray& ray, const Hit& hit, int depth, RayStats& stats,
              PrimaryHit* primary) const {
    const Scene& scene = ctx_.scene;
    SurfacePoint s = scene.surface(ray, hit);
    const Material& mat = scene.material(s.material);
    const ShadingMaterial sm = materials_.evaluate(hit, s);  // textures applied
    const PhongParams& ph = sm.phong;
    // Shade on the side the ray arrived from.
    Vec3 n = s.frontFace ? sm.n : -sm.n;
    Vec3 ng = s.frontFace ? s.ng : -s.ng;
    Vec3 wo = -normalize(ray.d);
    if (primary) {
      primary->hit = true;
      primary->depth = hit.t * length(ray.d);
      primary->position = s.p;
      primary->primitive = s.primitive, primary->instance = s.instance, primary->time = s.time;
      primary->normal = sm.n;
      primary->albedo = ph.diffuse;
      primary->objectId = scene.objectId(s.primitive, s.instance);
      primary->materialId = s.material;
    }
    if (sm.unlit) return sm.baseColor;  // KHR_materials_unlit: no lighting, no bounces

    Color L = ph.ambient * scene.environment.ambient + sm.emissive;
    // The map's unshadowed irradiance through the Lambert part of the Phong lobe: Whitted
    // samples no area of a light, so this is all the map gives (docs/scene-format.md).
    for (const EnvironmentIrradiance& env : environment_)
      L += ph.diffuse * env.irradiance(n) * (1.0f / kPi);
    // Whitted's direct light: the delta lights only (area lights are seen by reflection).
    for (int i : lights_.delta())
      L += directLight(lights_.light(size_t(i)), s.p, ng, s.time, n, wo, ph, stats);

    if (depth >= maxDepth_) return L;
    if (ph.reflectance > 0) {
      ++stats.secondaryRays;
      // Fresnel-Schlick with F0 = mirrorF0: tinted by a metal's base colour, rising to white at
      // grazing angles; exactly 1 for white F0 (stated Phong kr), so those images keep their bits.
      const Color kr = ph.reflectance * fresnelSchlick(ph.mirrorF0, dot(n, wo));
      L += kr * trace(spawnRay(s.p, ng, reflect(ray.d, n), s.time), depth + 1, stats, nullptr);
    }
    if (ph.transmittance > 0) {
      // Snell's law with eta = n_from / n_to; total internal reflection sends the light back.
      float eta = s.frontFace ? 1.0f / mat.ior : mat.ior;
      Vec3 d = normalize(ray.d), t;
      Vec3 next = refract(d, n, eta, t) ? t : reflect(d, n);
      ++stats.secondaryRays;
      L += ph.transmittance * trace(spawnRay(s.p, ng, next, s.time), depth + 1, stats, nullptr);
    }
    return L;
  }

  /// What a ray that leaves the scene sees: the infinite lights' radiance.
  Color background(const Vec3& d) const {
    Color L(0.0f);
    for (int i : lights_.infinite()) L += lights_.light(size_t(i)).Le(normalize(d));
    return L;
  }

  /// A delta light's irradiance (exact: its one sample) through the Phong lobe.
  Color directLight(const Light& light, const Vec3& p, const Vec3& ng, float time, const Vec3& n,
                    const Vec3& wo, const PhongParams& ph, RayStats& stats) const {
    const LightSample ls = light.sample({p, n, false}, {0.0f, 0.0f});
    if (!ls.valid() || dot(ls.wi, n) <= 0) return Color(0.0f);
    const Ray shadow = ls.infinite ? spawnRay(p, ng, ls.wi, time) : spawnRayTo(p, ng, ls.p, time);
    ++stats.shadowRays;
    const float T = transmittance(shadow);
    if (T == 0) return Color(0.0f);
    const Color direct = phongDirect(ph, n, wo, ls.wi, ls.L);
    return T < 1 ? direct * T : direct;
  }

  /// Layers of BLEND surfaces one ray passes before the rest is taken as black.
  static constexpr int kMaxBlendCrossings = 32;
  int maxDepth_;
  LightSet lights_;
  std::vector<EnvironmentIrradiance> environment_;  ///< per environment map
  MaterialEvaluator materials_;
  bool hasBlend_ = false;  ///< some material is alphaMode BLEND
};

}  // namespace

const std::vector<OptionSpec>& whittedOptions() {
  static const std::vector<OptionSpec> specs = {
      intOption("max-depth", 5, 0, 1000, "maximum recursion depth (reflection and refraction)"),
  };
  return specs;
}

std::unique_ptr<Integrator> makeWhitted(const RenderContext& ctx) {
  return std::make_unique<WhittedIntegrator>(declaring(ctx, whittedOptions()));
}

}  // namespace tray
