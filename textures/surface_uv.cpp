#include "textures/surface_uv.h"

#include "core/motion.h"

namespace tray {

namespace {

const std::vector<Vec2>& uvSet(const TriangleMesh& m, int set) {
  return set == 1 && !m.uvs1.empty() ? m.uvs1 : m.uvs;
}

}  // namespace

UvFrame surfaceUvFrame(const Scene& scene, const Hit& hit, const SurfacePoint& s, int set) {
  UvFrame f;
  const Primitive& prim = scene.primitives[s.primitive];
  Transform moved;  // a moving primitive: where the ray found it (core/motion.h)
  const Transform* placed = prim.instances ? &scene.placement(s.primitive, s.instance, moved)
                                           : placementAt(prim, s.time, moved);
  const Transform& toWorld = placed ? *placed : moved;
  if (prim.kind == Primitive::Kind::kShape) {
    f.uv = s.uv;
    Vec3 du, dv;
    prim.shape->uvDerivatives(toWorld.inversePoint(s.p), hit.normal, du, dv);
    f.dpdu = toWorld.vector(du);
    f.dpdv = toWorld.vector(dv);
    return f;
  }
  const TriangleMesh& m = scene.meshes[prim.mesh];
  const uint32_t* idx = &m.indices[3 * size_t(hit.triangle)];
  const float b0 = 1.0f - hit.b1 - hit.b2;
  const std::vector<Vec2>& uvs = uvSet(m, set);
  if (uvs.empty()) {
    f.uv = s.uv;
    return f;
  }
  const Vec2 &t0 = uvs[idx[0]], &t1 = uvs[idx[1]], &t2 = uvs[idx[2]];
  f.uv = {b0 * t0.x + hit.b1 * t1.x + hit.b2 * t2.x, b0 * t0.y + hit.b1 * t1.y + hit.b2 * t2.y};
  // Solve [dp02 dp12] = [dpdu dpdv] [duv02 duv12] for the triangle's constant derivatives.
  const Vec3 p0 = vertexAt(m, idx[0], s.time), p1 = vertexAt(m, idx[1], s.time),
             p2 = vertexAt(m, idx[2], s.time);
  const float du02 = t0.x - t2.x, dv02 = t0.y - t2.y, du12 = t1.x - t2.x, dv12 = t1.y - t2.y;
  const Vec3 dp02 = p0 - p2, dp12 = p1 - p2;
  const float det = du02 * dv12 - dv02 * du12;
  if (std::fabs(det) > 1e-12f) {
    const float inv = 1.0f / det;
    f.dpdu = toWorld.vector((dv12 * dp02 - dv02 * dp12) * inv);
    f.dpdv = toWorld.vector((du02 * dp12 - du12 * dp02) * inv);
  }
  if (!m.tangents.empty()) {
    Vec3 t = b0 * m.tangents[idx[0]] + hit.b1 * m.tangents[idx[1]] + hit.b2 * m.tangents[idx[2]];
    f.tangent = toWorld.vector(t);
    f.bitangentSign = m.tangentSigns[idx[0]];
    // A mirroring transform flips the bitangent's handedness relative to the tangent.
    if (toWorld.swapsHandedness()) f.bitangentSign = -f.bitangentSign;
  }
  return f;
}

}  // namespace tray
