#include "accel/embree_native.h"

#include <cstring>
#include <vector>

#include "core/error.h"
#include "shapes/curves.h"
#include "shapes/subdivision.h"

namespace tray {
namespace {

void copyBuffer(RTCGeometry g, RTCBufferType type, RTCFormat format, const void* data,
                size_t stride, size_t count) {
  // Embree-allocated (padded) buffers, as the triangle meshes' (embree_accelerator.cpp).
  void* dst = rtcSetNewGeometryBuffer(g, type, 0, format, stride, count);
  if (!dst) throw Error("Embree: cannot allocate a geometry buffer", Error::Kind::kRender);
  std::memcpy(dst, data, stride * count);
}

// Round curves are one-sided: a ray leaving the tube's inside (a fibre's TT or TRT direction,
// spawned on the far side of the surface) passes through. The hair BSDF models the path inside
// the fibre; Embree would otherwise report the tube's far wall (Chiang et al. 2016 and pbrt-v4
// treat a fibre as one scattering event).
void frontOnly(const RTCFilterFunctionNArguments* args) {
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const float dx = RTCRayN_dir_x(args->ray, args->N, i),
                dy = RTCRayN_dir_y(args->ray, args->N, i),
                dz = RTCRayN_dir_z(args->ray, args->N, i);
    const float nx = RTCHitN_Ng_x(args->hit, args->N, i), ny = RTCHitN_Ng_y(args->hit, args->N, i),
                nz = RTCHitN_Ng_z(args->hit, args->N, i);
    if (dx * nx + dy * ny + dz * nz > 0) args->valid[i] = 0;
  }
}

RTCGeometry curveGeometry(RTCDevice device, const Curves& c) {
  const bool round = c.shape() == CurveShape::kRound;
  const RTCGeometryType type =
      c.basis() == CurveBasis::kBezier
          ? (round ? RTC_GEOMETRY_TYPE_ROUND_BEZIER_CURVE : RTC_GEOMETRY_TYPE_FLAT_BEZIER_CURVE)
          : (round ? RTC_GEOMETRY_TYPE_ROUND_BSPLINE_CURVE : RTC_GEOMETRY_TYPE_FLAT_BSPLINE_CURVE);
  RTCGeometry g = rtcNewGeometry(device, type);
  copyBuffer(g, RTC_BUFFER_TYPE_VERTEX, RTC_FORMAT_FLOAT4, c.points().data(), sizeof(CurvePoint),
             c.points().size());
  copyBuffer(g, RTC_BUFFER_TYPE_INDEX, RTC_FORMAT_UINT, c.segments().data(), sizeof(uint32_t),
             c.segments().size());
  if (round) {
    rtcSetGeometryIntersectFilterFunction(g, frontOnly);
    rtcSetGeometryOccludedFilterFunction(g, frontOnly);
  }
  return g;
}

RTCGeometry subdivisionGeometry(RTCDevice device, const SubdivisionSurface& s) {
  const SubdivisionCage& c = s.cage();
  RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_SUBDIVISION);
  // 16-byte vertices with w = 0: Embree's subdivision code loads 4 floats per vertex and
  // asserts they are all finite (a 12-byte stride let rtcInterpolate read the padding).
  std::vector<float> padded(4 * c.positions.size(), 0.0f);
  for (size_t i = 0; i < c.positions.size(); ++i)
    std::memcpy(&padded[4 * i], &c.positions[i], sizeof(Vec3));
  copyBuffer(g, RTC_BUFFER_TYPE_VERTEX, RTC_FORMAT_FLOAT3, padded.data(), 4 * sizeof(float),
             c.positions.size());
  copyBuffer(g, RTC_BUFFER_TYPE_FACE, RTC_FORMAT_UINT, c.faceVertexCounts.data(), sizeof(uint32_t),
             c.faceVertexCounts.size());
  copyBuffer(g, RTC_BUFFER_TYPE_INDEX, RTC_FORMAT_UINT, c.indices.data(), sizeof(uint32_t),
             c.indices.size());
  if (!c.creaseEdges.empty()) {
    copyBuffer(g, RTC_BUFFER_TYPE_EDGE_CREASE_INDEX, RTC_FORMAT_UINT2, c.creaseEdges.data(),
               2 * sizeof(uint32_t), c.creaseEdges.size());
    copyBuffer(g, RTC_BUFFER_TYPE_EDGE_CREASE_WEIGHT, RTC_FORMAT_FLOAT, c.creaseWeights.data(),
               sizeof(float), c.creaseWeights.size());
  }
  if (!c.cornerVertices.empty()) {
    copyBuffer(g, RTC_BUFFER_TYPE_VERTEX_CREASE_INDEX, RTC_FORMAT_UINT, c.cornerVertices.data(),
               sizeof(uint32_t), c.cornerVertices.size());
    copyBuffer(g, RTC_BUFFER_TYPE_VERTEX_CREASE_WEIGHT, RTC_FORMAT_FLOAT, c.cornerWeights.data(),
               sizeof(float), c.cornerWeights.size());
  }
  rtcSetGeometrySubdivisionMode(
      g, 0,
      c.smoothBoundary ? RTC_SUBDIVISION_MODE_SMOOTH_BOUNDARY : RTC_SUBDIVISION_MODE_PIN_BOUNDARY);
  rtcSetGeometryTessellationRate(g, c.tessellationRate);
  return g;
}

}  // namespace

RTCGeometry embreeNativeGeometry(RTCDevice device, const Shape& shape) {
  if (auto* c = dynamic_cast<const Curves*>(&shape)) return curveGeometry(device, *c);
  if (auto* s = dynamic_cast<const SubdivisionSurface*>(&shape))
    return subdivisionGeometry(device, *s);
  return nullptr;
}

bool embreeNativeIsSubdivision(const Shape& shape) {
  return dynamic_cast<const SubdivisionSurface*>(&shape) != nullptr;
}

void embreeSubdivisionNormal(RTCGeometry g, Hit& hit) {
  float p[3], du[3], dv[3];
  RTCInterpolateArguments a{};
  a.geometry = g;
  a.primID = hit.triangle;
  a.u = hit.uv.x;
  a.v = hit.uv.y;
  a.bufferType = RTC_BUFFER_TYPE_VERTEX;
  a.bufferSlot = 0;
  a.P = p;
  a.dPdu = du;
  a.dPdv = dv;
  a.valueCount = 3;
  rtcInterpolate(&a);
  Vec3 n = cross(Vec3(du[0], du[1], du[2]), Vec3(dv[0], dv[1], dv[2]));
  // A degenerate derivative (an extraordinary vertex's corner): the tessellation's normal.
  if (!(length(n) > 0) || !isFinite(n)) n = hit.normal;
  const Vec2 e = octahedralEncode(n);
  hit.b1 = e.x, hit.b2 = e.y;
}

}  // namespace tray
