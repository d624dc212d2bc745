// Embree's own curves and Catmull-Clark subdivision surfaces (shapes/curves.h,
// shapes/subdivision.h, accel/embree_native.h; docs/curves-subdivision.md): hits and surfaces
// against closed forms, the limit surface of a cube against an independent Catmull-Clark
// refinement, the in-house BVH's refusal, and the glTF scenes of tools/make_curves_scenes.py.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include "accel/registry.h"
#include "core/error.h"
#include "core/scene.h"
#include "gltf/gltf_loader.h"
#include "shapes/curves.h"
#include "shapes/subdivision.h"

namespace tray {
namespace {

Scene sceneOf(std::shared_ptr<const Shape> shape) {
  Scene s;
  Primitive p;
  p.kind = Primitive::Kind::kShape;
  p.shape = std::move(shape);
  p.name = "test shape";
  s.primitives.push_back(p);
  s.finalize();
  return s;
}

// Four collinear, evenly spaced control points along x with radius r: a B-spline segment from
// x = 1 to 2 ((P0 + 4 P1 + P2) / 6 to (P1 + 4 P2 + P3) / 6), a Bezier one from 0 to 3.
std::shared_ptr<Curves> straightCurve(CurveBasis basis, CurveShape shape, float r) {
  std::vector<CurvePoint> pts;
  for (int k = 0; k < 4; ++k) pts.push_back({Vec3(float(k), 0, 0), r});
  return std::make_shared<Curves>(basis, shape, pts, std::vector<uint32_t>{0});
}

TEST(Curves, RoundCurveIsATubeWithItsNormalAndTangent) {
  Scene scene = sceneOf(straightCurve(CurveBasis::kBSpline, CurveShape::kRound, 0.1f));
  auto accel = makeAccelerator("embree", scene);
  // Straight down at offset z = 0.05 from the axis: the tube's top at y = sqrt(0.1^2 - 0.05^2).
  Ray ray{{1.5f, 5, 0.05f}, {0, -1, 0}};
  Hit hit;
  ASSERT_TRUE(accel->intersect(ray, hit));
  const float y = std::sqrt(0.01f - 0.0025f);
  EXPECT_NEAR(hit.t, 5 - y, 2e-3f);
  EXPECT_NEAR(hit.uv.x, 0.5f, 0.01f);  // Embree's u along the segment
  SurfacePoint s = scene.surface(ray, hit);
  EXPECT_NEAR(std::fabs(s.tangent.x), 1.0f, 1e-4f);
  EXPECT_NEAR(s.n.y, y / 0.1f, 0.02f);
  EXPECT_NEAR(s.n.z, 0.5f, 0.02f);
  EXPECT_NEAR(s.n.x, 0.0f, 0.02f);
  EXPECT_TRUE(s.frontFace);
}

TEST(Curves, RoundCurveIsOneSided) {
  // A ray leaving the tube's inside (a fibre's transmitted direction) passes through it.
  Scene scene = sceneOf(straightCurve(CurveBasis::kBSpline, CurveShape::kRound, 0.1f));
  auto accel = makeAccelerator("embree", scene);
  Ray inside{{1.5f, 0, 0}, {0, 1, 0}};
  Hit hit;
  EXPECT_FALSE(accel->intersect(inside, hit));
  EXPECT_FALSE(accel->occluded(inside));
  Ray outside{{1.5f, 5, 0}, {0, -1, 0}};
  EXPECT_TRUE(accel->occluded(outside));
}

TEST(Curves, FlatRibbonFacesTheRayAndCarriesTheFibreOffset) {
  Scene scene = sceneOf(straightCurve(CurveBasis::kBSpline, CurveShape::kFlat, 0.1f));
  auto accel = makeAccelerator("embree", scene);
  Ray ray{{1.5f, 5, 0.05f}, {0, -1, 0}};
  Hit hit;
  ASSERT_TRUE(accel->intersect(ray, hit));
  EXPECT_NEAR(hit.t, 5.0f, 2e-3f);  // the ribbon passes through the axis, facing the ray
  EXPECT_NEAR(std::fabs(hit.uv.y), 0.5f, 0.02f);  // half way out: v = +-0.5
  SurfacePoint s = scene.surface(ray, hit);
  EXPECT_NEAR(s.ng.y, 1.0f, 1e-4f);
  // The shading normal is a round fibre's at h = v: 0.5 sideways, cos(asin 0.5) up.
  EXPECT_NEAR(std::fabs(s.n.z), 0.5f, 0.02f);
  EXPECT_NEAR(s.n.y, std::sqrt(0.75f), 0.02f);
}

TEST(Curves, BezierInterpolatesItsEnds) {
  Scene scene = sceneOf(straightCurve(CurveBasis::kBezier, CurveShape::kRound, 0.1f));
  auto accel = makeAccelerator("embree", scene);
  Hit hit;
  EXPECT_TRUE(accel->intersect(Ray{{0.2f, 5, 0}, {0, -1, 0}}, hit));
  EXPECT_TRUE(accel->intersect(Ray{{2.8f, 5, 0}, {0, -1, 0}}, hit));
  EXPECT_FALSE(accel->intersect(Ray{{-0.3f, 5, 0}, {0, -1, 0}}, hit));
  // The B-spline of the same points spans only x in [1, 2].
  Scene bs = sceneOf(straightCurve(CurveBasis::kBSpline, CurveShape::kRound, 0.1f));
  EXPECT_FALSE(makeAccelerator("embree", bs)->intersect(Ray{{0.5f, 5, 0}, {0, -1, 0}}, hit));
}

TEST(Curves, StrandsToSegments) {
  size_t bad = 99;
  EXPECT_EQ(curveSegmentsOfStrands(CurveBasis::kBSpline, {4, 6}, &bad),
            (std::vector<uint32_t>{0, 4, 5, 6}));
  EXPECT_EQ(curveSegmentsOfStrands(CurveBasis::kBezier, {7, 4}, &bad),
            (std::vector<uint32_t>{0, 3, 7}));
  EXPECT_TRUE(curveSegmentsOfStrands(CurveBasis::kBezier, {7, 5}, &bad).empty());
  EXPECT_EQ(bad, 1u);
}

// ---- Catmull-Clark: an independent refinement of a closed quad mesh (Catmull & Clark 1978:
// face points, edge points, then vertices (Q + 2R + (n - 3) S) / n), to compare Embree's limit
// surface with.
struct QuadMesh {
  std::vector<Vec3> p;
  std::vector<std::array<uint32_t, 4>> quads;
};

QuadMesh refine(const QuadMesh& m) {
  QuadMesh out;
  const size_t nv = m.p.size();
  std::map<std::pair<uint32_t, uint32_t>, std::vector<uint32_t>> edgeFaces;
  auto key = [](uint32_t a, uint32_t b) { return std::make_pair(std::min(a, b), std::max(a, b)); };
  std::vector<Vec3> facePt(m.quads.size());
  for (size_t f = 0; f < m.quads.size(); ++f) {
    Vec3 c(0.0f);
    for (uint32_t v : m.quads[f]) c += m.p[v];
    facePt[f] = c * 0.25f;
    for (int k = 0; k < 4; ++k)
      edgeFaces[key(m.quads[f][size_t(k)], m.quads[f][size_t((k + 1) % 4)])].push_back(uint32_t(f));
  }
  std::map<std::pair<uint32_t, uint32_t>, uint32_t> edgeIndex;
  out.p.resize(nv);
  std::vector<Vec3> sumF(nv, Vec3(0.0f)), sumR(nv, Vec3(0.0f));
  std::vector<int> valence(nv, 0), faces(nv, 0);
  for (auto& [e, fs] : edgeFaces) {
    const Vec3 mid = 0.5f * (m.p[e.first] + m.p[e.second]);
    Vec3 ep = (m.p[e.first] + m.p[e.second] + facePt[fs[0]] + facePt[fs[1]]) * 0.25f;
    edgeIndex[e] = uint32_t(out.p.size());
    out.p.push_back(ep);
    for (uint32_t v : {e.first, e.second}) sumR[v] += mid, ++valence[v];
  }
  for (size_t f = 0; f < m.quads.size(); ++f)
    for (uint32_t v : m.quads[f]) sumF[v] += facePt[f], ++faces[v];
  for (size_t v = 0; v < nv; ++v) {
    const float n = float(valence[v]);
    out.p[v] = (sumF[v] / float(faces[v]) + 2.0f * sumR[v] / n + (n - 3) * m.p[v]) / n;
  }
  for (size_t f = 0; f < m.quads.size(); ++f) {
    const uint32_t fp = uint32_t(out.p.size());
    out.p.push_back(facePt[f]);
    const auto& q = m.quads[f];
    for (int k = 0; k < 4; ++k) {
      const uint32_t v = q[size_t(k)], next = edgeIndex[key(v, q[size_t((k + 1) % 4)])],
                     prev = edgeIndex[key(q[size_t((k + 3) % 4)], v)];
      out.quads.push_back({v, next, fp, prev});
    }
  }
  return out;
}

const float kCubeP[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                            {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
const uint32_t kCubeQ[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                               {2, 3, 7, 6}, {1, 2, 6, 5}, {0, 4, 7, 3}};

SubdivisionCage cubeCage() {
  SubdivisionCage c;
  for (auto& p : kCubeP) c.positions.push_back({p[0], p[1], p[2]});
  for (auto& q : kCubeQ) {
    c.faceVertexCounts.push_back(4);
    c.indices.insert(c.indices.end(), q, q + 4);
  }
  return c;
}

// Nearest hit of a ray with the quads (two triangles each, Moller-Trumbore), or infinity.
float hitQuads(const QuadMesh& m, const Vec3& o, const Vec3& d) {
  float best = kInfinity;
  auto tri = [&](const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 e1 = b - a, e2 = c - a, pv = cross(d, e2);
    const float det = dot(e1, pv);
    if (std::fabs(det) < 1e-12f) return;
    const Vec3 tv = o - a;
    const float u = dot(tv, pv) / det;
    const Vec3 qv = cross(tv, e1);
    const float v = dot(d, qv) / det, t = dot(e2, qv) / det;
    if (u >= 0 && v >= 0 && u + v <= 1 && t > 0 && t < best) best = t;
  };
  for (const auto& q : m.quads) {
    tri(m.p[q[0]], m.p[q[1]], m.p[q[2]]);
    tri(m.p[q[0]], m.p[q[2]], m.p[q[3]]);
  }
  return best;
}

// Rays from outside towards the centre, along 48 directions spread over the sphere (a
// Fibonacci lattice): the limit surface's distance from the centre in each direction.
std::vector<Vec3> directions() {
  std::vector<Vec3> d;
  const int n = 48;
  for (int i = 0; i < n; ++i) {
    const float z = 1 - (2 * i + 1) / float(n), r = std::sqrt(1 - z * z),
                phi = float(i) * 2.39996323f;
    d.push_back({r * std::cos(phi), r * std::sin(phi), z});
  }
  return d;
}

TEST(Subdivision, CubeLimitSurfaceMatchesAnIndependentRefinement) {
  Scene scene = sceneOf(std::make_shared<SubdivisionSurface>(cubeCage()));
  auto accel = makeAccelerator("embree", scene);
  QuadMesh ref;
  for (auto& p : kCubeP) ref.p.push_back({p[0], p[1], p[2]});
  for (auto& q : kCubeQ) ref.quads.push_back({q[0], q[1], q[2], q[3]});
  for (int level = 0; level < 5; ++level) ref = refine(ref);  // 6144 quads
  double worst = 0;
  for (const Vec3& d : directions()) {
    const Vec3 o = 4.0f * d;
    Hit hit;
    ASSERT_TRUE(accel->intersect(Ray{o, -d}, hit));
    const float want = hitQuads(ref, o, -d);
    ASSERT_TRUE(std::isfinite(want));
    worst = std::max(worst, double(std::fabs(hit.t - want)));
    // The shading normal is the limit surface's: outward, near the radial direction here.
    SurfacePoint s = scene.surface(Ray{o, -d}, hit);
    EXPECT_GT(dot(s.n, d), 0.5f);
    EXPECT_GT(dot(s.ng, d), 0.5f);
  }
  // Level 5 sits within ~1e-3 of the limit for this cage (half size 1); Embree's rate-16
  // tessellation within the same.
  EXPECT_LT(worst, 6e-3) << "largest radial difference";
  std::printf("largest radial difference from the level-5 refinement: %.2e\n", worst);
  // The comparison has teeth: the cage's face (x = 1) and the limit surface's face centre
  // (x = 0.840 by both) are far apart next to the tolerance.
  Hit axis;
  ASSERT_TRUE(accel->intersect(Ray{{4, 0, 0}, {-1, 0, 0}}, axis));
  EXPECT_NEAR(4 - axis.t, 4 - hitQuads(ref, {4, 0, 0}, {-1, 0, 0}), 6e-3f);
  EXPECT_LT(4 - axis.t, 0.85f);
  EXPECT_GT(4 - axis.t, 0.83f);
}

TEST(Subdivision, InfinitelySharpEdgesKeepTheCube) {
  // Every edge creased at infinity: edges stay straight and corners fixed, so the limit is
  // the cage itself (DeRose et al. 1998's sharp rules).
  SubdivisionCage c = cubeCage();
  for (auto& q : kCubeQ)
    for (int k = 0; k < 4; ++k)
      if (q[k] < q[(k + 1) % 4]) {
        c.creaseEdges.push_back({q[k], q[(k + 1) % 4]});
        c.creaseWeights.push_back(kInfinity);
      }
  ASSERT_EQ(c.creaseEdges.size(), 12u);
  Scene scene = sceneOf(std::make_shared<SubdivisionSurface>(c));
  auto accel = makeAccelerator("embree", scene);
  Hit hit;
  ASSERT_TRUE(accel->intersect(Ray{{4, 0.3f, -0.2f}, {-1, 0, 0}}, hit));
  EXPECT_NEAR(hit.t, 3.0f, 2e-3f);
  ASSERT_TRUE(accel->intersect(Ray{{0.9f, 4, 0.9f}, {0, -1, 0}}, hit));
  EXPECT_NEAR(hit.t, 3.0f, 2e-3f);
}

TEST(EmbreeOnly, TheInHouseBvhRefusesCurvesAndSubdivisionByName) {
  for (auto shape :
       {std::shared_ptr<const Shape>(straightCurve(CurveBasis::kBezier, CurveShape::kRound, 0.1f)),
        std::shared_ptr<const Shape>(std::make_shared<SubdivisionSurface>(cubeCage()))})
    for (const char* name : {"bvh", "bvh-gs", "naive"}) {
      Scene scene = sceneOf(shape);
      scene.sourcePath = "hair.gltf";
      try {
        makeAccelerator(name, scene);
        ADD_FAILURE() << name << " accepted an Embree-only shape";
      } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("hair.gltf"), std::string::npos) << what;
        EXPECT_NE(what.find("Embree-only"), std::string::npos) << what;
        EXPECT_NE(what.find("test shape"), std::string::npos) << what;
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
      }
    }
}

TEST(CurvesGltf, GeneratedScenesLoad) {
  Scene fur = loadGltf(TRAY_SOURCE_DIR "/scenes/curves/fur_patch.gltf");
  int curves = 0, hair = 0;
  for (const Primitive& p : fur.primitives)
    if (auto* c = dynamic_cast<const Curves*>(p.shape.get())) {
      ++curves;
      EXPECT_EQ(c->basis(), CurveBasis::kBSpline);
      EXPECT_EQ(c->shape(), CurveShape::kRound);
      EXPECT_EQ(c->segments().size(), 256u * 3u);  // 16 x 16 strands of 6 points
      hair += fur.material(p.material).hair.enabled;
    }
  EXPECT_EQ(curves, 3);
  EXPECT_EQ(hair, 3);
  Scene ribbons = loadGltf(TRAY_SOURCE_DIR "/scenes/curves/ribbons.gltf");
  for (const Primitive& p : ribbons.primitives)
    if (auto* c = dynamic_cast<const Curves*>(p.shape.get())) {
      EXPECT_EQ(c->basis(), CurveBasis::kBezier);
      EXPECT_EQ(c->shape(), CurveShape::kFlat);
    }
  Scene sub = loadGltf(TRAY_SOURCE_DIR "/scenes/curves/subdiv_cube.gltf");
  std::vector<const SubdivisionSurface*> cages;
  for (const Primitive& p : sub.primitives)
    if (auto* s = dynamic_cast<const SubdivisionSurface*>(p.shape.get())) cages.push_back(s);
  ASSERT_EQ(cages.size(), 3u);
  EXPECT_EQ(cages[1]->cage().creaseEdges.size(), 4u);
  // The triangle mesh as a cage: its 8 corners welded, 12 triangles.
  EXPECT_EQ(cages[2]->cage().positions.size(), 8u);
  EXPECT_EQ(cages[2]->cage().faceVertexCounts, std::vector<uint32_t>(12, 3));
}

}  // namespace
}  // namespace tray
