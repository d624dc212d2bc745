#include "integrators/surface_vertex.h"

#include "integrators/surface_rules.h"

namespace tray {

SurfaceVertices::SurfaceVertices(const RenderContext& ctx, int samplesPerPixel)
    : scene_(ctx.scene), materials_(ctx.scene, ctx.camera, samplesPerPixel) {}

VertexKind SurfaceVertices::at(Ray& ray, const Hit& hit, MediumStack& media, int& nullCrossings,
                               SurfaceVertex& v) const {
  v.s = scene_.surface(ray, hit);
  const SurfacePoint& s = v.s;
  v.m = &scene_.material(s.material);
  const Material& m = *v.m;
  v.wo = -normalize(ray.d);
  // Nested dielectrics (Schmidt & Budge 2002): a surface of a medium not in effect is passed.
  v.refractive = isRefractive(m);
  v.eta = m.ior / media.currentIor();
  if (v.refractive) {
    const MediumStack::Interface iface = media.interface(s.material, m, s.frontFace);
    if (!iface.real) {
      media.cross(s.material, m, s.frontFace);
      if (++nullCrossings > kMaxNullCrossings) return VertexKind::kGaveUp;
      setSpawnRay(ray, s.p, s.ng, ray.d, s.time);
      return VertexKind::kPassed;
    }
    v.eta = iface.etaT / iface.etaI;
  }
  v.sm = materials_.evaluate(hit, s);
  hideOuterLayersInside(v.sm, v.refractive, s.frontFace);
  v.n = s.frontFace ? v.sm.n : -v.sm.n;
  return VertexKind::kSurface;
}

}  // namespace tray
