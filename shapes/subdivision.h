#pragma once
#include <cstdint>
#include <utility>
#include <vector>

#include "core/shape.h"

namespace tray {

/// A Catmull-Clark subdivision surface (Catmull & Clark 1978) over a polygon control cage,
/// intersected by Embree's RTC_GEOMETRY_TYPE_SUBDIVISION, which tessellates the limit surface
/// adaptively per patch at `tessellationRate` quads per edge (docs/curves-subdivision.md;
/// TRAY_subdivision). Faces have 3 to 15 vertices (Embree's range); edge and vertex creases
/// sharpen the limit (DeRose et al. 1998's semi-sharp creases, as Embree and OpenSubdiv).
/// Embree only: the in-house BVH has no subdivision evaluator (embreeOnly).
/// Hits carry the face in Hit::triangle, Embree's uv in Hit::uv, the tessellation's normal in
/// Hit::normal and the limit surface's normal (Embree's rtcInterpolate dP/du x dP/dv),
/// octahedral-encoded (Cigolle et al. 2014), in Hit::b1 and b2: shade() decodes it as the
/// shading normal, so the surface looks smooth while rays leave the tessellated one.
struct SubdivisionCage {
  std::vector<Vec3> positions;
  std::vector<uint32_t> faceVertexCounts;
  std::vector<uint32_t> indices;  ///< faceVertexCounts' sum
  std::vector<std::pair<uint32_t, uint32_t>> creaseEdges;
  std::vector<float> creaseWeights;  ///< per crease edge; infinity: a sharp edge
  std::vector<uint32_t> cornerVertices;
  std::vector<float> cornerWeights;  ///< per corner vertex
  float tessellationRate = 16;       ///< Embree's quads per patch edge
  /// Boundary rule: true smooths boundary edges (Embree's RTC_SUBDIVISION_MODE_SMOOTH_BOUNDARY),
  /// false pins boundary vertices and edges (PIN_BOUNDARY).
  bool smoothBoundary = true;
};

class SubdivisionSurface final : public Shape {
 public:
  explicit SubdivisionSurface(SubdivisionCage cage);
  const SubdivisionCage& cage() const { return cage_; }
  /// The cage's bounds: a Catmull-Clark limit surface lies within its control points' hull.
  Bounds3 bounds() const override { return bounds_; }
  bool intersect(const Ray&, Hit&) const override { return false; }
  void intervals(const Ray&, std::vector<Interval>&) const override {}
  bool isSolid() const override { return false; }
  const char* embreeOnly() const override;
  bool shade(const Ray& local, const Hit& hit, ShapeShading& out) const override;

 private:
  SubdivisionCage cage_;
  Bounds3 bounds_;
};

/// Octahedral unit-vector encoding (Cigolle et al. 2014, "A Survey of Efficient
/// Representations for Independent Unit Vectors"): the accelerator packs the limit normal into
/// two floats, shade() unpacks it.
Vec2 octahedralEncode(const Vec3& n);
Vec3 octahedralDecode(Vec2 e);

}  // namespace tray
