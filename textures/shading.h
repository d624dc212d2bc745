#pragma once
// "Evaluate the material at a surface point": the one place where textures meet shading.
// Integrators (Whitted's Phong, the path tracer's BSDF) and the albedo AOV read the result.
#include <memory>
#include <vector>

#include "core/camera.h"
#include "core/hit.h"
#include "core/material.h"
#include "core/scene.h"
#include "textures/surface_uv.h"
#include "textures/texture_sampler.h"

namespace tray {

/// uv footprint of one pixel at a surface point: the camera's pixel spread (Camera::
/// pixelSpread) projected along the viewing direction onto the tangent plane (normal ng), then
/// expressed in uv through dp/du, dp/dv by least squares (pbrt-v4 §10.1.1), times `scale`.
UvFootprint pixelFootprint(const UvFrame& frame, const Vec3& p, const Vec3& ng,
                           const Camera& camera, float scale);

/// Evaluates materials at surface points, sampling their textures. Creates a TextureSampler only
/// when the scene has textures, and touches it only for materials that use them.
class MaterialEvaluator {
 public:
  /// samplesPerPixel narrows the footprint (pbrt-v4: max(1/8, 1/sqrt(spp)) of a pixel), since
  /// the pixel's samples already average over its area. The scene's materials are read once
  /// here: they must not change while the evaluator lives.
  MaterialEvaluator(const Scene& scene, const Camera& camera, int samplesPerPixel);
  ~MaterialEvaluator();
  ShadingMaterial evaluate(const Hit& hit, const SurfacePoint& s) const;
  /// The material's factors when they are all of evaluate()'s result at this hit (no texture,
  /// vertex colour or blend coverage): evaluate() returns them with n and clearcoatN set to
  /// s.n. Null otherwise. Lets a caller that needs a few fields skip the copy.
  const ShadingMaterial* plainFactors(const Hit& hit, const SurfacePoint& s) const {
    const Prebuilt& pre = prebuilt_[size_t(s.material)];
    return pre.plain && !(hit.material < 0 && coloredMesh_[hit.primitive]) ? &pre.factors : nullptr;
  }
  /// Places a copy of a material's factors at s (its normals): evaluate()'s result where
  /// plainFactors gave them.
  static void placeAt(ShadingMaterial& factors, const SurfacePoint& s) {
    factors.n = s.n;
    factors.clearcoatN = s.n;
    if (factors.hair) factors.tangent = s.tangent;  // the hair BSDF's fibre axis
  }
  /// Whether some material samples a texture (else prefetchTextures never does anything).
  bool textured() const { return sampler_ != nullptr; }
  /// Prefetches the texels that evaluate() at s will read of its material's base colour,
  /// metal-roughness, emissive and normal textures, where TextureSampler::prefetch knows them
  /// from the TEXCOORD_0 uv alone. Changes nothing a lookup returns.
  void prefetchTextures(const SurfacePoint& s) const;

 private:
  /// evaluate() past the factors: multiplies `out` by the vertex colour, blend coverage and
  /// textures at s, then finishes Phong. Out of line: the plain path then pushes no registers
  /// and reserves no stack for uv frames.
  [[gnu::noinline]] void modulate(const Hit& hit, const SurfacePoint& s,
                                  ShadingMaterial& out) const;
  /// Phong parameters after the base colour was modulated by `base` (texture x vertex colour).
  static void finishPhong(const Material& m, ShadingMaterial& out, const Color& base);
  Vec3 normalMapped(const ShadingMaterial& out, const UvFrame& f, const Color& texel, float scale,
                    const SurfacePoint& s) const;
  const Scene& scene_;
  const Camera& camera_;
  float footprintScale_;
  std::shared_ptr<const TextureSampler> sampler_;  ///< the scene's (Scene::textureSampler)
  /// Per material: ShadingMaterial::of it (normal unset); whether textures are sampled; whether
  /// the factors are the result wherever there is no vertex colour (no texture, no blending).
  /// Copying the prebuilt factors and testing two flags rather than ShadingMaterial::of's field
  /// by field copy and the material's, primitive's and mesh's fields: evaluate() of an
  /// untextured material 103 -> 50 instructions per vertex (callgrind, Cornell box).
  struct Prebuilt {
    ShadingMaterial factors;
    bool textured = false, plain = false;
  };
  std::vector<Prebuilt> prebuilt_;
  std::vector<uint8_t> coloredMesh_;  ///< per primitive: a mesh with vertex colours (COLOR_0)
};

}  // namespace tray
