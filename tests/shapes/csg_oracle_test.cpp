// Random CSG trees of boxes and spheres, traced through Scene + accelerator (embree and bvh)
// and checked ray by ray against an exact point-membership oracle (issue 18: "CSG leaks at
// edges where operands meet"). Ray-level tests: csg_test.cpp; image tests: csg_render_test.cpp.
//
// Why an oracle and not a mesh twin: spheres have no exact mesh, and a mesh of a box-only
// boolean result has its own ambiguity exactly where the leaks are (rays through silhouette
// edges). The oracle is the solid's signed-distance bound f(p), evaluated in double from the
// same float matrices and sizes the renderer gets: exact distance per primitive (box, sphere,
// placed by rigid transforms only), combined by min (union), max (intersection) and
// max(a, -b) (difference). f < 0 exactly inside, and f is 1-Lipschitz, so f(p) < -kEps means
// the whole kEps-ball around p is solid and f(p) > kEps that it is empty: a classification no
// float rounding of the renderer (a few 1e-6 at these scales) can flip.
//
// Per camera ray (origin outside the solid), the oracle samples the line at the midpoint (and
// quarter points) of every stretch between consecutive primitive boundaries, in double, and
// requires:
//   leak:    no robustly inside sample (f < -kEps) before the renderer's hit (a miss when
//            there is one is a ray passing through the solid);
//   phantom: the hit point lies on the boundary, f(hit) <= kEps;
//   normal:  where exactly one primitive surface lies within kEdge of the hit point (away from
//            edges, corners and coincident faces), the shading normal is that surface's
//            outward normal of the result within kNormalCos.
// Rays: every pixel centre of 300 trees at 64x64; 32 points per tree on lines where faces of
// two different primitives meet (and on coincident faces), each hit by 9 rays offset across
// the line by 0, +-2e-5, +-6e-5, +-2e-4, +-6e-4; and every 8th row of 4 trees at 1024x1024.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "accel/registry.h"
#include "core/camera.h"
#include "shapes/csg.h"
#include "tests/scene_builder.h"
#include "tests/shapes/csg_random_tree.h"

namespace tray {
namespace {

using namespace tray::test;
using namespace tray::test::csg_tree;

constexpr double kEps = 1e-5;          // robust inside / outside margin (scene size ~2)
constexpr double kEdge = 5e-5;         // normals are checked farther than this from any edge
constexpr double kNormalCos = 0.9999995;  // 1e-3 rad

// --- Checking rays -------------------------------------------------------------------------

struct Tally {
  long rays = 0, mustHit = 0, hits = 0, normalsChecked = 0;
  long leaks = 0, phantoms = 0, normals = 0;
  std::vector<std::string> examples;
  void add(const Tally& o) {
    rays += o.rays, mustHit += o.mustHit, hits += o.hits, normalsChecked += o.normalsChecked;
    leaks += o.leaks, phantoms += o.phantoms, normals += o.normals;
    for (const auto& e : o.examples)
      if (examples.size() < 12) examples.push_back(e);
  }
  long failures() const { return leaks + phantoms + normals; }
};

/// The outward normal of the result at boundary point p, if exactly one primitive face (or
/// sphere) lies within kEdge of p; false near edges, corners and coincident faces.
bool oracleNormal(const Tree& tree, const D3& p, D3& normal) {
  int features = 0;
  D3 n;
  for (size_t i = 0; i < tree.prims.size(); ++i) {
    const Prim& q = tree.prims[i];
    if (std::fabs(tree.primDistance(int(i), p)) > kEdge) continue;
    D3 lp = q.toLocal.point(p), ln;
    if (q.sphere) {
      ++features;
      ln = lp;
    } else {
      for (int a = 0; a < 3; ++a)
        for (int side = 0; side < 2; ++side) {
          double face = side ? q.hi[a] : q.lo[a];
          if (std::fabs(lp[a] - face) > kEdge) continue;
          bool within = true;  // on the face's rectangle, up to kEdge
          for (int b = 0; b < 3; ++b)
            if (b != a && (lp[b] < q.lo[b] - kEdge || lp[b] > q.hi[b] + kEdge)) within = false;
          if (!within) continue;
          ++features;
          ln = D3();
          ln[a] = side ? 1 : -1;
        }
    }
    // Normals transform by the inverse transpose of toWorld: the rows of toLocal.
    if (features == 1 && !(ln[0] == 0 && ln[1] == 0 && ln[2] == 0)) {
      D3 w;
      for (int k = 0; k < 3; ++k)
        w[k] = q.toLocal.m[0][k] * ln[0] + q.toLocal.m[1][k] * ln[1] + q.toLocal.m[2][k] * ln[2];
      n = unit(w);
    }
  }
  if (features != 1) return false;
  // Outward for the result: the direction in which f grows (subtracted faces flip).
  double h = 0.5 * kEdge;
  normal = tree.f(p + h * n) > tree.f(p - h * n) ? n : -1.0 * n;
  return true;
}

/// One ray from outside the solid, through both accelerators.
void checkRay(const Tree& tree, const Scene& scene, const std::vector<const Accelerator*>& accels,
              const Ray& ray, Tally& tally, const std::string& what) {
  D3 o = d3(ray.o), d = d3(ray.d);
  double dl = len(d);
  std::vector<double> ts;
  tree.boundaries(o, d, ts);
  // The first robustly inside sample along the ray, if any.
  double tInside = -1;
  for (size_t i = 0; i + 1 < ts.size() && tInside < 0; ++i) {
    if (ts[i + 1] <= 0) continue;
    double a = std::max(ts[i], 0.0), b = ts[i + 1];
    for (double w : {0.25, 0.5, 0.75})
      if (tree.f(o + (a + w * (b - a)) * d) < -kEps) {
        tInside = a + w * (b - a);
        break;
      }
  }
  for (size_t k = 0; k < accels.size(); ++k) {
    ++tally.rays;
    tally.mustHit += tInside >= 0;
    Hit hit;
    bool found = accels[k]->intersect(ray, hit);
    tally.hits += found;
    char buf[400];
    auto note = [&](const char* kind, double value) {
      if (tally.examples.size() >= 12) return;
      std::snprintf(buf, sizeof buf,
                    "%s %s [%s]: o=(%.9g %.9g %.9g) d=(%.9g %.9g %.9g) hit=%d t=%.9g "
                    "inside at t=%.9g value=%.3g",
                    kind, what.c_str(), k == 0 ? "embree" : "bvh", ray.o.x, ray.o.y, ray.o.z, ray.d.x,
                    ray.d.y, ray.d.z, int(found), found ? hit.t : -1.0, tInside, value);
      tally.examples.push_back(buf);
    };
    if (tInside >= 0 && (!found || hit.t > tInside + kEps / dl)) {
      ++tally.leaks;
      note("leak", found ? tree.f(o + double(hit.t) * d) : 0.0);
      continue;
    }
    if (!found) continue;
    D3 p = o + double(hit.t) * d;
    double fp = tree.f(p);
    if (fp > kEps) {
      ++tally.phantoms;
      note("phantom", fp);
      continue;
    }
    D3 expected;
    if (!oracleNormal(tree, p, expected)) continue;
    ++tally.normalsChecked;
    SurfacePoint s = scene.surface(ray, hit);
    double c = dot(expected, unit(d3(s.ng)));
    if (c < kNormalCos) {
      ++tally.normals;
      note("normal", c);
    }
  }
}

struct Case {
  Tree tree;
  Scene scene;
  std::unique_ptr<Accelerator> embree, bvh;
  uint32_t seed;
  explicit Case(uint32_t s) : tree(makeTree(s)), seed(s) {
    addShape(scene, tree.csg, tree.place, addMaterial(scene, diffuse(Color(0.8f))));
    scene.finalize();
    embree = makeAccelerator("embree", scene);
    bvh = makeAccelerator("bvh", scene);
  }
  std::vector<const Accelerator*> accels() const { return {embree.get(), bvh.get()}; }
  CameraDesc camera(uint32_t seed) const {
    Rng rng(seed * 7919u + 17u);
    double z = rng.range(-0.9, 0.9), phi = rng.range(0, 2 * kPi), r = std::sqrt(1 - z * z);
    Vec3 eye = 6.0f * Vec3(float(r * std::cos(phi)), float(z), float(r * std::sin(phi)));
    Vec3 centre{tree.place.m[0][3], tree.place.m[1][3], tree.place.m[2][3]};
    return lookAt(centre + eye, centre, 0.55f);
  }
};

/// Points on lines where faces of two different primitives meet (and on coincident faces),
/// on the boundary of the result, with the direction of the line (zero on coincident faces).
struct EdgePoint {
  D3 p, along;
};

struct Face {
  D3 centre, n, u, v;  ///< world; u, v: in-plane half-extent vectors
};

std::vector<Face> boxFaces(const Prim& q) {
  std::vector<Face> faces;
  D3 c = 0.5 * (q.lo + q.hi), h = 0.5 * (q.hi - q.lo);
  for (int a = 0; a < 3; ++a)
    for (int s : {-1, 1}) {
      D3 lc = c, ln, lu, lv;
      lc[a] += s * h[a];
      ln[a] = s;
      int b = (a + 1) % 3, e = (a + 2) % 3;
      lu[b] = h[b];
      lv[e] = h[e];
      faces.push_back({q.toWorld.point(lc), unit(q.toWorld.vec(ln)), q.toWorld.vec(lu),
                       q.toWorld.vec(lv)});
    }
  return faces;
}

/// Clips the line x + s dir to the face rectangle (in its plane): s in [s0, s1].
void clipToFace(const Face& f, const D3& x, const D3& dir, double& s0, double& s1) {
  for (const D3& axis : {f.u, f.v}) {
    double l2 = dot(axis, axis), a = dot(x - f.centre, axis) / l2, b = dot(dir, axis) / l2;
    if (std::fabs(b) < 1e-15) {
      if (std::fabs(a) > 1) s0 = 1, s1 = 0;
      continue;
    }
    double lo = (-1 - a) / b, hi = (1 - a) / b;
    s0 = std::max(s0, std::min(lo, hi));
    s1 = std::min(s1, std::max(lo, hi));
  }
}

std::vector<EdgePoint> edgePoints(const Tree& tree, Rng& rng, int wanted) {
  std::vector<std::vector<Face>> faces(tree.prims.size());
  for (size_t i = 0; i < tree.prims.size(); ++i)
    if (!tree.prims[i].sphere) faces[i] = boxFaces(tree.prims[i]);
  std::vector<EdgePoint> out;
  for (int attempt = 0; attempt < 400 * wanted && int(out.size()) < wanted; ++attempt) {
    size_t i = size_t(rng.below(int(tree.prims.size()))), j = size_t(rng.below(int(tree.prims.size())));
    if (i == j || faces[i].empty()) continue;
    const Face& F = faces[i][size_t(rng.below(6))];
    D3 p, along;
    if (tree.prims[j].sphere) {  // the circle where the sphere cuts F's plane
      const Prim& q = tree.prims[j];
      D3 c = q.toWorld.point(D3());
      double dist = dot(c - F.centre, F.n), r2 = q.radius * q.radius - dist * dist;
      if (r2 <= 0) continue;
      double phi = rng.range(0, 2 * kPi);
      D3 e1 = unit(F.u), e2 = unit(F.v);
      D3 radial = std::cos(phi) * e1 + std::sin(phi) * e2;
      p = c - dist * F.n + std::sqrt(r2) * radial;
      along = cross(F.n, radial);
      double s0 = 0, s1 = 0;
      clipToFace(F, p, along, s0, s1);
      if (s0 > s1) continue;
    } else {
      const Face& G = faces[j][size_t(rng.below(6))];
      along = cross(F.n, G.n);
      if (len(along) < 1e-9) {  // parallel: coincident faces only
        if (std::fabs(dot(G.centre - F.centre, F.n)) > 1e-9) continue;
        p = F.centre + rng.range(-1, 1) * F.u + rng.range(-1, 1) * F.v;
        double s0 = 0, s1 = 0;
        clipToFace(G, p, F.u, s0, s1);
        if (s0 > s1) continue;
        along = D3();
      } else {
        // The point of both planes nearest F's centre, then the segment inside both faces.
        along = unit(along);
        D3 m = cross(along, F.n);  // in F's plane, across the line
        double s = dot(G.centre - F.centre, G.n) / dot(m, G.n);
        D3 x = F.centre + s * m;
        double s0 = -1e9, s1 = 1e9;
        clipToFace(F, x, along, s0, s1);
        clipToFace(G, x, along, s0, s1);
        if (s0 > s1) continue;
        p = x + rng.range(s0, s1) * along;
      }
    }
    if (std::fabs(tree.f(p)) > 1e-7) continue;  // buried: not on the result's boundary
    out.push_back({p, along});
  }
  return out;
}

/// Rays from `eye` across the edge point: offsets 0, +-2e-5, +-6e-5, +-2e-4, +-6e-4.
void checkEdgeRays(const Case& c, const Vec3& eye, const EdgePoint& e, Rng& rng, Tally& tally) {
  D3 o = d3(eye), toward = unit(e.p - o);
  D3 across = cross(toward, e.along);
  if (len(across) < 1e-6) across = cross(toward, {{rng.range(-1, 1), 1, rng.range(-1, 1)}});
  across = unit(across);
  for (double off : {0.0, 2e-5, -2e-5, 6e-5, -6e-5, 2e-4, -2e-4, 6e-4, -6e-4}) {
    D3 d = unit(e.p + off * across - o);
    Ray ray{eye, {float(d[0]), float(d[1]), float(d[2])}};
    checkRay(c.tree, c.scene, c.accels(), ray, tally, "edge ray of tree " + std::to_string(c.seed));
  }
}

void report(const char* name, const Tally& t) {
  std::printf("%s: %ld rays (%ld must hit, %ld hits, %ld normals checked): %ld leaks, "
              "%ld phantom hits, %ld normals off\n",
              name, t.rays, t.mustHit, t.hits, t.normalsChecked, t.leaks, t.phantoms, t.normals);
  for (const auto& e : t.examples) std::printf("  %s\n", e.c_str());
}

constexpr int kTrees = 300, kSize = 64, kEdgePoints = 32;

TEST(CsgOracle, RandomTreesSmallImagesAndEdgeRays) {
  Tally image, edges;
  int solidTrees = 0;
  for (uint32_t seed = 1; seed <= kTrees; ++seed) {
    Case c(seed);
    CameraDesc desc = c.camera(seed);
    auto camera = Camera::create(desc, kSize, kSize);
    Tally t;
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x)
        checkRay(c.tree, c.scene, c.accels(), camera->generateRay(x + 0.5f, y + 0.5f), t,
                 "pixel of tree " + std::to_string(seed));
    solidTrees += t.mustHit > 0;
    image.add(t);
    Rng rng(seed + 1000003u);
    Vec3 eye = desc.toWorld.point(Vec3(0.0f));
    for (const EdgePoint& e : edgePoints(c.tree, rng, kEdgePoints))
      checkEdgeRays(c, eye, e, rng, edges);
  }
  report("64x64 pixels", image);
  report("edge rays", edges);
  EXPECT_GT(solidTrees, kTrees * 3 / 4);       // most random trees are solid and in view
  EXPECT_GT(edges.rays, long(kTrees) * 2 * 9 * 8);  // edge points are found
  EXPECT_EQ(image.leaks, 0);
  EXPECT_EQ(image.phantoms, 0);
  EXPECT_EQ(image.normals, 0);
  EXPECT_EQ(edges.leaks, 0);
  EXPECT_EQ(edges.phantoms, 0);
  EXPECT_EQ(edges.normals, 0);
}

TEST(CsgOracle, LargeImagesEveryEighthRow) {
  Tally all;
  for (uint32_t seed : {3u, 11u, 42u, 77u}) {
    Case c(seed);
    auto camera = Camera::create(c.camera(seed), 1024, 1024);
    for (int y = 0; y < 1024; y += 8)
      for (int x = 0; x < 1024; ++x)
        checkRay(c.tree, c.scene, c.accels(), camera->generateRay(x + 0.5f, y + 0.5f), all,
                 "1024 pixel of tree " + std::to_string(seed));
  }
  report("1024x1024, every 8th row", all);
  EXPECT_GT(all.mustHit, 20000);
  EXPECT_EQ(all.leaks, 0);
  EXPECT_EQ(all.phantoms, 0);
  EXPECT_EQ(all.normals, 0);
}

}  // namespace
}  // namespace tray
