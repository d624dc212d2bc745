#include "textures/shading.h"

#include <cmath>
#include <new>

#include "core/sampling.h"
#include "core/unbuilt.h"
#include "textures/alpha.h"
#include "textures/tangent_frame.h"

namespace tray {

UvFootprint pixelFootprint(const UvFrame& f, const Vec3& p, const Vec3& ng, const Camera& camera,
                           float scale) {
  UvFootprint out;
  out.uv = f.uv;
  Vec3 dx, dy, dir;
  camera.pixelSpread(p, dx, dy, dir);
  // Move the offsets along the viewing direction onto the tangent plane; at grazing angles the
  // footprint stretches, capped at 100x.
  float cosine = dot(ng, dir);
  if (std::fabs(cosine) < 1e-2f) cosine = cosine < 0 ? -1e-2f : 1e-2f;
  const Vec3 dpdx = scale * (dx - dir * (dot(ng, dx) / cosine));
  const Vec3 dpdy = scale * (dy - dir * (dot(ng, dy) / cosine));
  const float a00 = dot(f.dpdu, f.dpdu), a01 = dot(f.dpdu, f.dpdv), a11 = dot(f.dpdv, f.dpdv);
  const float det = a00 * a11 - a01 * a01;
  if (!(det > 0) || !std::isfinite(det)) return out;  // no parameterisation: point sample
  auto solve = [&](const Vec3& d) {
    const float bu = dot(f.dpdu, d), bv = dot(f.dpdv, d);
    Vec2 r{(a11 * bu - a01 * bv) / det, (a00 * bv - a01 * bu) / det};
    auto clamp = [](float v) { return std::isfinite(v) ? std::clamp(v, -1e8f, 1e8f) : 0.0f; };
    return Vec2{clamp(r.x), clamp(r.y)};
  };
  out.dx = solve(dpdx);
  out.dy = solve(dpdy);
  return out;
}

MaterialEvaluator::MaterialEvaluator(const Scene& scene, const Camera& camera, int spp)
    : scene_(scene),
      camera_(camera),
      footprintScale_(std::max(0.125f, 1.0f / std::sqrt(float(std::max(spp, 1))))) {
  // One sampler per scene, whatever the number of evaluators and renders: its MIP pyramids
  // are made once (a lookup's value does not depend on which sampler made it).
  if (!scene.textures.empty())
    sampler_ = std::static_pointer_cast<const TextureSampler>(scene.textureSampler.get([&scene] {
      return std::make_shared<const TextureSampler>(scene.textures, scene.textureCacheMB);
    }));
  prebuilt_.reserve(scene.materials.size());
  for (const Material& m : scene.materials) {
    const bool textured = sampler_ && m.hasTextures();
    prebuilt_.push_back(
        {ShadingMaterial::of(m, Vec3()), textured,
         !textured && m.alphaMode != AlphaMode::kBlend && !(m.layers.anisotropyStrength > 0)});
  }
  coloredMesh_.reserve(scene.primitives.size());
  for (const Primitive& p : scene.primitives)
    coloredMesh_.push_back(p.kind == Primitive::Kind::kMesh && p.mesh < scene.meshes.size() &&
                           !scene.meshes[p.mesh].colors.empty());
}

MaterialEvaluator::~MaterialEvaluator() = default;

Vec3 MaterialEvaluator::normalMapped(const ShadingMaterial& out, const UvFrame& f,
                                     const Color& texel, float scale, const SurfacePoint& s) const {
  // glTF 2.0 §3.9.3: tangent-space normal = (2 rgb - 1) with x, y scaled by normalTexture.scale;
  // frame (t, b, n) with b = sign * cross(n, t), t the vertex tangent or dp/du.
  const Vec3& n = out.n;
  Vec3 t, b;
  tangentFrame(n, f, t, b);
  Vec3 m{(2.0f * texel.x - 1.0f) * scale, (2.0f * texel.y - 1.0f) * scale, 2.0f * texel.z - 1.0f};
  Vec3 mapped = m.x * t + m.y * b + m.z * n;
  float ml = length(mapped);
  // A tilt past the geometric surface would shade the back side: keep the interpolated normal.
  if (!(ml > 0) || !std::isfinite(ml) || dot(mapped, s.ng) * dot(n, s.ng) <= 0) return n;
  return mapped / ml;
}

ShadingMaterial MaterialEvaluator::evaluate(const Hit& hit, const SurfacePoint& s) const {
  // ShadingMaterial::of(m, s.n). Most vertices: the factors alone (no vertex colour, blend
  // coverage or texture).
  ShadingMaterial out = prebuilt_[size_t(s.material)].factors;
  placeAt(out, s);
  if (plainFactors(hit, s)) return out;
  modulate(hit, s, out);
  return out;
}

void MaterialEvaluator::prefetchTextures(const SurfacePoint& s) const {
  if (!sampler_ || !prebuilt_[size_t(s.material)].textured) return;
  const Material& m = scene_.material(s.material);
  for (const TextureRef* ref :
       {&m.baseColorTexture, &m.metallicRoughnessTexture, &m.emissiveTexture, &m.normalTexture})
    if (ref->valid() && ref->texCoord == 0) sampler_->prefetch(*ref, s.uv);
}

void MaterialEvaluator::modulate(const Hit& hit, const SurfacePoint& s,
                                 ShadingMaterial& out) const {
  const Material& m = scene_.material(s.material);
  // COLOR_0 multiplies the base colour (glTF 2.0 §3.9.2); a CSG override material has none.
  const TriangleMesh* mesh = nullptr;
  if (const Primitive& p = scene_.primitives[hit.primitive];
      p.kind == Primitive::Kind::kMesh && hit.material < 0)
    mesh = &scene_.meshes[p.mesh];
  const bool vertexColored = mesh && !mesh->colors.empty();
  const Color vertex =
      vertexColored ? vertexColor(*mesh, hit.triangle, hit.b1, hit.b2) : Color(1.0f);
  if (vertexColored) out.baseColor *= vertex;
  if (mesh && m.alphaMode == AlphaMode::kBlend) out.alpha = coverage(scene_, hit);
  if (!prebuilt_[size_t(s.material)].textured) {
    // KHR_materials_anisotropy without a texture still needs the tangent frame's direction.
    if (m.layers.anisotropyStrength > 0)
      out.anisotropyDirection = anisotropyDirection(out.n, surfaceUvFrame(scene_, hit, s, 0),
                                                    m.layers.anisotropyRotation, {}, false);
    if (vertexColored) finishPhong(m, out, vertex);
    return;
  }

  // One uv frame per uv set in use (glTF allows TEXCOORD_0 and _1 to differ per texture), and
  // one pixel footprint per set: it depends on the set's frame and the point alone, so the
  // textures that share a set share it (the helmets' four lookups per vertex made it four
  // times: 10% of that scene's render, callgrind).
  // Built when first asked for (core/unbuilt.h: a default UvFrame pair cost a 96-byte
  // `rep stos` per textured vertex).
  Unbuilt<UvFrame> frames[2];
  Unbuilt<UvFootprint> footprints[2];
  bool have[2] = {false, false}, haveFootprint[2] = {false, false};
  auto frameOf = [&](int set) -> const UvFrame& {
    const int k = set == 1 ? 1 : 0;
    if (!have[k]) new (&frames[k].value) UvFrame(surfaceUvFrame(scene_, hit, s, k)), have[k] = true;
    return frames[k].value;
  };
  auto footprintOf = [&](int set) -> const UvFootprint& {
    const int k = set == 1 ? 1 : 0;
    if (!haveFootprint[k])
      new (&footprints[k].value)
          UvFootprint(pixelFootprint(frameOf(k), s.p, s.ng, camera_, footprintScale_)),
          haveFootprint[k] = true;
    return footprints[k].value;
  };
  auto lookup = [&](const TextureRef& ref) {
    if (!TextureSampler::footprintMatters(ref))
      return sampler_->sample(ref, {frameOf(ref.texCoord).uv, {}, {}});
    return sampler_->sample(ref, footprintOf(ref.texCoord));
  };
  Color base(1.0f);
  if (m.baseColorTexture.valid()) out.baseColor *= (base = lookup(m.baseColorTexture));
  if (m.metallicRoughnessTexture.valid()) {
    // glTF 2.0 §3.9.2: roughness in G, metalness in B.
    Color mr = lookup(m.metallicRoughnessTexture);
    out.roughness *= mr.y;
    out.metallic *= mr.z;
  }
  if (m.emissiveTexture.valid()) out.emissive *= lookup(m.emissiveTexture);
  if (m.normalTexture.valid()) {
    out.n = normalMapped(out, frameOf(m.normalTexture.texCoord), lookup(m.normalTexture),
                         m.normalTexture.scale, s);
  }
  if (m.layers.hasTextures()) {
    const MaterialLayers& l = m.layers;
    if (l.specularTexture.valid()) {  // KHR_materials_specular: the strength is in alpha
      out.specular *= textureAlpha(scene_.textures[size_t(l.specularTexture.image)],
                                   l.specularTexture, frameOf(l.specularTexture.texCoord).uv);
    }
    if (l.specularColorTexture.valid()) out.specularColor *= lookup(l.specularColorTexture);
    // KHR_materials_clearcoat: strength in R, roughness in G; the coat's own normal map.
    if (l.clearcoatTexture.valid()) out.clearcoat *= lookup(l.clearcoatTexture).x;
    if (l.clearcoatRoughnessTexture.valid())
      out.clearcoatRoughness *= lookup(l.clearcoatRoughnessTexture).y;
    // KHR_materials_sheen: colour in RGB, roughness in alpha.
    if (l.sheenColorTexture.valid()) out.sheenColor *= lookup(l.sheenColorTexture);
    if (l.sheenRoughnessTexture.valid()) {
      out.sheenRoughness *=
          textureAlpha(scene_.textures[size_t(l.sheenRoughnessTexture.image)],
                       l.sheenRoughnessTexture, frameOf(l.sheenRoughnessTexture.texCoord).uv);
    }
    // KHR_materials_diffuse_transmission: the factor in A, the colour in RGB.
    if (l.diffuseTransmissionTexture.valid()) {
      out.diffuseTransmission *= textureAlpha(
          scene_.textures[size_t(l.diffuseTransmissionTexture.image)], l.diffuseTransmissionTexture,
          frameOf(l.diffuseTransmissionTexture.texCoord).uv);
    }
    if (l.diffuseTransmissionColorTexture.valid())
      out.diffuseTransmissionColor *= lookup(l.diffuseTransmissionColorTexture);
    // KHR_materials_iridescence: factor in R, thickness between min and max in G.
    if (l.iridescenceTexture.valid()) out.iridescence *= lookup(l.iridescenceTexture).x;
    if (l.iridescenceThicknessTexture.valid()) {
      const float g = lookup(l.iridescenceThicknessTexture).y;
      out.iridescenceThickness =
          l.iridescenceThicknessMin + (l.iridescenceThicknessMax - l.iridescenceThicknessMin) * g;
    }
    if (l.clearcoatNormalTexture.valid()) {
      ShadingMaterial geometric = out;
      geometric.n = s.n;
      out.clearcoatN =
          normalMapped(geometric, frameOf(l.clearcoatNormalTexture.texCoord),
                       lookup(l.clearcoatNormalTexture), l.clearcoatNormalTexture.scale, s);
    }
  }
  // KHR_materials_anisotropy: the direction in the frame of the (normal-mapped) normal; the
  // texture's B scales the strength.
  if (m.layers.anisotropyStrength > 0) {
    const TextureRef& ref = m.layers.anisotropyTexture;
    const Color texel = ref.valid() ? lookup(ref) : Color(1.0f);
    out.anisotropy *= texel.z;
    out.anisotropyDirection =
        anisotropyDirection(out.n, frameOf(ref.valid() ? ref.texCoord : 0),
                            m.layers.anisotropyRotation, {texel.x, texel.y}, ref.valid());
  }
  finishPhong(m, out, base * vertex);
}

void MaterialEvaluator::finishPhong(const Material& m, ShadingMaterial& out, const Color& base) {
  if (m.hasPhong) {
    // Stated Phong colours are modulated by the base colour texture and vertex colour (OpenGL's
    // MODULATE).
    out.phong.diffuse *= base;
    out.phong.ambient *= base;
  } else {
    out.phong = phongFromPbr(out.baseColor, out.metallic, out.roughness, out.transmission);
    phongLayers(out.phong, out.baseColor, out.metallic, out.specular, out.specularColor,
                out.clearcoat, out.clearcoatRoughness);
  }
}

}  // namespace tray
