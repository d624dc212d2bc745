#include "gltf/tray_curves.h"

#include <cmath>
#include <map>
#include <string>
#include <tuple>

#include "gltf/gltf_accessors.h"
#include "shapes/curves.h"
#include "shapes/subdivision.h"

namespace tray {
namespace {

const tinygltf::Accessor& accessorOf(const GltfContext& ctx, ExtensionReader& r,
                                     const std::string& key, int& index) {
  index = r.integer(key, -1);
  if (index < 0 || index >= int(ctx.model.accessors.size()))
    r.fail("'" + key + "' must name an accessor (0 to " +
           std::to_string(int(ctx.model.accessors.size()) - 1) + ")");
  return ctx.model.accessors[size_t(index)];
}

std::vector<float> floatsOf(const GltfContext& ctx, ExtensionReader& r, const std::string& key,
                            int type, const char* typeName) {
  int index;
  const tinygltf::Accessor& a = accessorOf(ctx, r, key, index);
  if (a.type != type || a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
    r.fail("'" + key + "' must be a " + typeName + " float accessor");
  std::vector<float> v = readFloats(ctx, index);
  for (float x : v)
    if (!std::isfinite(x)) r.fail("'" + key + "' holds a value that is not finite");
  return v;
}

std::vector<uint32_t> indicesOf(const GltfContext& ctx, ExtensionReader& r,
                                const std::string& key) {
  int index;
  const tinygltf::Accessor& a = accessorOf(ctx, r, key, index);
  const int c = a.componentType;
  if (a.type != TINYGLTF_TYPE_SCALAR ||
      (c != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && c != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
       c != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
    r.fail("'" + key + "' must be a SCALAR unsigned byte, short or int accessor");
  return readIndices(ctx, index);
}

std::vector<Vec3> vec3sOf(const std::vector<float>& f) {
  std::vector<Vec3> v(f.size() / 3);
  for (size_t i = 0; i < v.size(); ++i) v[i] = {f[3 * i], f[3 * i + 1], f[3 * i + 2]};
  return v;
}

// A glTF mesh's triangles as a cage, vertices welded by exact position: exporters split
// vertices at uv and normal seams, which would cut the limit surface apart.
void cageFromMesh(const GltfContext& ctx, ExtensionReader& r, int meshIndex, SubdivisionCage& c) {
  if (meshIndex < 0 || meshIndex >= int(ctx.model.meshes.size()))
    r.fail("'mesh' refers to missing mesh " + std::to_string(meshIndex));
  std::map<std::tuple<float, float, float>, uint32_t> welded;
  for (const tinygltf::Primitive& p : ctx.model.meshes[size_t(meshIndex)].primitives) {
    if (p.mode != -1 && p.mode != TINYGLTF_MODE_TRIANGLES)
      r.fail("'mesh' " + std::to_string(meshIndex) + " has a primitive that is not triangles");
    auto pos = p.attributes.find("POSITION");
    if (pos == p.attributes.end()) r.fail("'mesh' has a primitive without POSITION");
    std::vector<Vec3> points = vec3sOf(readFloats(ctx, pos->second));
    std::vector<uint32_t> idx;
    if (p.indices >= 0) {
      idx = readIndices(ctx, p.indices);
    } else {
      for (uint32_t i = 0; i < points.size(); ++i) idx.push_back(i);
    }
    if (idx.size() % 3) r.fail("'mesh' has a triangle list whose length is not a multiple of 3");
    for (uint32_t i : idx) {
      if (i >= points.size()) r.fail("'mesh' has an index past its vertices");
      const Vec3& q = points[i];
      auto [it, added] =
          welded.emplace(std::make_tuple(q.x, q.y, q.z), uint32_t(c.positions.size()));
      if (added) c.positions.push_back(q);
      c.indices.push_back(it->second);
    }
  }
  c.faceVertexCounts.assign(c.indices.size() / 3, 3);
}

void readCreases(const GltfContext& ctx, ExtensionReader& r, SubdivisionCage& c) {
  const uint32_t n = uint32_t(c.positions.size());
  if (r.has("creases")) {
    std::vector<uint32_t> e = indicesOf(ctx, r, "creases");
    std::vector<float> w = floatsOf(ctx, r, "creaseWeights", TINYGLTF_TYPE_SCALAR, "SCALAR");
    if (e.size() % 2 || w.size() != e.size() / 2)
      r.fail("'creases' must hold vertex pairs, one 'creaseWeights' value per pair");
    for (size_t k = 0; k < w.size(); ++k) {
      if (e[2 * k] >= n || e[2 * k + 1] >= n) r.fail("'creases' refers to a missing vertex");
      if (!(w[k] >= 0)) r.fail("'creaseWeights' must not be negative");
      c.creaseEdges.push_back({e[2 * k], e[2 * k + 1]});
    }
    c.creaseWeights = w;
  }
  if (r.has("corners")) {
    c.cornerVertices = indicesOf(ctx, r, "corners");
    c.cornerWeights = floatsOf(ctx, r, "cornerWeights", TINYGLTF_TYPE_SCALAR, "SCALAR");
    if (c.cornerWeights.size() != c.cornerVertices.size())
      r.fail("'cornerWeights' must hold one value per 'corners' vertex");
    for (size_t k = 0; k < c.cornerVertices.size(); ++k)
      if (c.cornerVertices[k] >= n || !(c.cornerWeights[k] >= 0))
        r.fail("'corners' refers to a missing vertex or has a negative weight");
  }
}

}  // namespace

std::shared_ptr<const Shape> parseCurves(const GltfContext& ctx, ExtensionReader& r) {
  const std::string basisName = r.string("basis", "bspline"),
                    profile = r.string("profile", "round");
  if (basisName != "bspline" && basisName != "bezier")
    r.fail("'basis' must be \"bspline\" or \"bezier\"");
  if (profile != "round" && profile != "flat") r.fail("'profile' must be \"round\" or \"flat\"");
  const CurveBasis basis = basisName == "bezier" ? CurveBasis::kBezier : CurveBasis::kBSpline;
  std::vector<float> f = floatsOf(ctx, r, "points", TINYGLTF_TYPE_VEC4, "VEC4");
  std::vector<CurvePoint> points(f.size() / 4);
  for (size_t i = 0; i < points.size(); ++i) {
    points[i] = {{f[4 * i], f[4 * i + 1], f[4 * i + 2]}, f[4 * i + 3]};
    if (!(points[i].radius >= 0))
      r.fail("'points' has a negative radius at point " + std::to_string(i));
  }
  std::vector<uint32_t> segments;
  if (r.has("strands") && r.has("segments")) r.fail("give 'strands' or 'segments', not both");
  if (r.has("segments")) {
    segments = indicesOf(ctx, r, "segments");
    for (uint32_t s : segments)
      if (uint64_t(s) + 3 >= points.size())
        r.fail("'segments' has a segment starting at " + std::to_string(s) +
               " without 4 control points");
  } else {
    std::vector<uint32_t> counts = r.has("strands")
                                       ? indicesOf(ctx, r, "strands")
                                       : std::vector<uint32_t>{uint32_t(points.size())};
    uint64_t total = 0;
    for (uint32_t n : counts) total += n;
    if (total != points.size())
      r.fail("'strands' counts " + std::to_string(total) + " points, 'points' has " +
             std::to_string(points.size()));
    size_t bad = 0;
    segments = curveSegmentsOfStrands(basis, counts, &bad);
    if (segments.empty())
      r.fail("strand " + std::to_string(bad) + " has " +
             std::to_string(counts.empty() ? 0 : counts[bad]) +
             (basis == CurveBasis::kBezier ? " points: a Bezier strand needs 3k + 1 >= 4"
                                           : " points: a B-spline strand needs at least 4"));
  }
  if (segments.empty()) r.fail("has no curve segment");
  return std::make_shared<Curves>(basis, profile == "flat" ? CurveShape::kFlat : CurveShape::kRound,
                                  std::move(points), std::move(segments));
}

std::shared_ptr<const Shape> parseSubdivision(const GltfContext& ctx, ExtensionReader& r) {
  SubdivisionCage c;
  if (r.has("mesh")) {
    if (r.has("positions") || r.has("indices") || r.has("faceVertexCounts"))
      r.fail("give 'mesh' or a cage ('positions', 'faceVertexCounts', 'indices'), not both");
    cageFromMesh(ctx, r, r.integer("mesh", -1), c);
  } else {
    c.positions = vec3sOf(floatsOf(ctx, r, "positions", TINYGLTF_TYPE_VEC3, "VEC3"));
    c.faceVertexCounts = indicesOf(ctx, r, "faceVertexCounts");
    c.indices = indicesOf(ctx, r, "indices");
  }
  uint64_t sum = 0;
  for (uint32_t n : c.faceVertexCounts) {
    // Embree's range of face sizes (RTC_GEOMETRY_TYPE_SUBDIVISION).
    if (n < 3 || n > 15) r.fail("has a face of " + std::to_string(n) + " vertices (3 to 15)");
    sum += n;
  }
  if (sum != c.indices.size())
    r.fail("'faceVertexCounts' sum to " + std::to_string(sum) + " but 'indices' has " +
           std::to_string(c.indices.size()));
  for (uint32_t i : c.indices)
    if (i >= c.positions.size())
      r.fail("'indices' refers to a missing vertex " + std::to_string(i));
  if (c.faceVertexCounts.empty()) r.fail("has no face");
  c.tessellationRate = float(r.number("tessellationRate", 16.0, 1.0, 4096.0));
  const std::string boundary = r.string("boundary", "smooth");
  if (boundary != "smooth" && boundary != "pin") r.fail("'boundary' must be \"smooth\" or \"pin\"");
  c.smoothBoundary = boundary == "smooth";
  readCreases(ctx, r, c);
  return std::make_shared<SubdivisionSurface>(std::move(c));
}

}  // namespace tray
