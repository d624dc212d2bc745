#pragma once
// Alpha coverage of mesh surfaces (glTF alphaMode MASK and BLEND), evaluated where a ray meets a
// triangle. Both accelerators call alphaAccepts from their any-hit test (Embree's filter
// callbacks in accel/embree_alpha_filter.cpp, the BVH's triangle loop in
// accel/bvh_accelerator.cpp), so they agree hit for hit; shading (textures/shading.cpp) and
// Whitted's blend read the same alpha.
#include <cstdint>

#include "core/hit.h"
#include "core/material.h"
#include "core/ray.h"
#include "core/scene.h"

namespace tray {

/// True if hits on a mesh with this material need the any-hit test (alphaMode not OPAQUE).
/// Opaque meshes never reach the functions below: they cost nothing.
inline bool needsAlphaTest(const Material& m) {
  return m.alphaMode != AlphaMode::kOpaque;
}

/// Linear alpha of texture image `ref.image` at uv (before the reference's transform): bilinear
/// in the finest level with the sampler's wrap modes, 1 if the image has no alpha channel.
/// No footprint: a cut-out edge stays as sharp as the texture at every distance.
float textureAlpha(const TextureImage& image, const TextureRef& ref, Vec2 uv);

/// COLOR_0 of a mesh at barycentrics (b1, b2) of `triangle`: RGB (1 if absent) and alpha.
Color vertexColor(const TriangleMesh& mesh, uint32_t triangle, float b1, float b2);
float vertexAlpha(const TriangleMesh& mesh, uint32_t triangle, float b1, float b2);

/// baseColorFactor alpha x base-colour texture alpha x COLOR_0 alpha at a mesh hit (glTF 2.0
/// §3.9.4). Before alphaMode is applied: see coverage().
float meshAlpha(const Scene& scene, const TriangleMesh& mesh, uint32_t triangle, float b1,
                float b2);

/// Coverage in [0, 1] of a mesh hit (hit.primitive a mesh): 1 for OPAQUE; 0 or 1 for MASK
/// (alpha >= alphaCutoff is covered); alpha for BLEND.
float coverage(const Scene& scene, const Hit& hit);

/// A number in [0, 1) fixed by the world-space ray and the triangle: the random decision of
/// stochastic transparency. A hash rather than a sampler dimension, so that the decision is the
/// same in every accelerator and in intersect and occluded alike, and so that scenes without
/// BLEND surfaces draw exactly the sampler numbers they drew before.
float alphaHash(const Ray& worldRay, uint32_t primitive, uint32_t triangle);

/// The any-hit test: false if the ray passes through triangle `triangle` of mesh primitive
/// `primitive` at (b1, b2). MASK: cut out below alphaCutoff. BLEND: by worldRay.blend, either
/// always a hit (kHit) or a hit with probability alpha (kStochastic, decided by alphaHash).
bool alphaAccepts(const Scene& scene, const Ray& worldRay, uint32_t primitive, uint32_t triangle,
                  float b1, float b2);

}  // namespace tray
