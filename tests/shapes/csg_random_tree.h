#pragma once
// Random CSG trees of boxes and spheres for csg_oracle_test.cpp: each built both as a Csg shape
// (what the renderer traces) and as the oracle's double-precision primitives (a signed-distance
// bound of the solid, exact per primitive), from deterministic random numbers.
#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "core/math.h"
#include "shapes/csg.h"

namespace tray::test::csg_tree {

// --- Deterministic random numbers (no std::uniform_*_distribution: it differs by library) -

struct Rng {
  std::mt19937 g;
  explicit Rng(uint32_t seed) : g(seed) {}
  double u() { return double(g() >> 5) * (1.0 / 134217728.0); }  // [0, 1), 27 bits
  double range(double a, double b) { return a + (b - a) * u(); }
  int below(int n) { return int(g() % uint32_t(n)); }
  /// A multiple of 1/8 in [a, b] (a, b multiples of 1/8): faces of different boxes coincide.
  float grid(float a, float b) { return a + 0.125f * float(below(int((b - a) * 8) + 1)); }
};

// --- Double-precision affine maps for the oracle ------------------------------------------

struct D3 {
  double v[3] = {0, 0, 0};
  double& operator[](int i) { return v[i]; }
  double operator[](int i) const { return v[i]; }
};
inline D3 d3(const Vec3& a) { return {{a.x, a.y, a.z}}; }
inline D3 operator+(D3 a, D3 b) { return {{a[0] + b[0], a[1] + b[1], a[2] + b[2]}}; }
inline D3 operator-(D3 a, D3 b) { return {{a[0] - b[0], a[1] - b[1], a[2] - b[2]}}; }
inline D3 operator*(double s, D3 a) { return {{s * a[0], s * a[1], s * a[2]}}; }
inline double dot(D3 a, D3 b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline D3 cross(D3 a, D3 b) {
  return {{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}};
}
inline double len(D3 a) { return std::sqrt(dot(a, a)); }
inline D3 unit(D3 a) { return (1.0 / len(a)) * a; }

struct DAffine {
  double m[3][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}};
  static DAffine of(const Mat4& f) {
    DAffine a;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 4; ++j) a.m[i][j] = f.m[i][j];
    return a;
  }
  D3 point(D3 p) const { return vec(p) + D3{{m[0][3], m[1][3], m[2][3]}}; }
  D3 vec(D3 p) const {
    D3 r;
    for (int i = 0; i < 3; ++i) r[i] = m[i][0] * p[0] + m[i][1] * p[1] + m[i][2] * p[2];
    return r;
  }
};
inline DAffine operator*(const DAffine& a, const DAffine& b) {
  DAffine r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j) {
      double s = j == 3 ? a.m[i][3] : 0.0;
      for (int k = 0; k < 3; ++k) s += a.m[i][k] * b.m[k][j];
      r.m[i][j] = s;
    }
  return r;
}
inline DAffine inverse(const DAffine& a) {
  const auto& m = a.m;
  double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
               m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
               m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  DAffine r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      int i1 = (j + 1) % 3, i2 = (j + 2) % 3, j1 = (i + 1) % 3, j2 = (i + 2) % 3;
      r.m[i][j] = (m[i1][j1] * m[i2][j2] - m[i1][j2] * m[i2][j1]) / det;
    }
  D3 t = r.vec({{m[0][3], m[1][3], m[2][3]}});
  for (int i = 0; i < 3; ++i) r.m[i][3] = -t[i];
  return r;
}

// --- Random trees, built both as a Csg and as the oracle's primitives ----------------------

struct Prim {
  bool sphere = false;
  D3 lo, hi;  ///< box, local space
  double radius = 0;
  DAffine toWorld, toLocal;
};

struct Node {
  int prim = -1;  ///< leaf: index into Tree::prims
  CsgOp op = CsgOp::kUnion;
  std::vector<Node> kids;
};

struct Tree {
  std::vector<Prim> prims;
  Node root;
  std::shared_ptr<const Shape> csg;  ///< the root Csg
  Mat4 place;       ///< CSG object space -> world

  /// Signed-distance bound of the solid at world point p (see the file comment).
  double f(const D3& p) const { return eval(root, p); }
  double primDistance(int i, const D3& pw) const {
    const Prim& q = prims[size_t(i)];
    D3 p = q.toLocal.point(pw);
    if (q.sphere) return len(p) - q.radius;
    D3 out;
    double inside = -1e300;
    for (int a = 0; a < 3; ++a) {
      double c = 0.5 * (q.lo[a] + q.hi[a]), h = 0.5 * (q.hi[a] - q.lo[a]);
      double d = std::fabs(p[a] - c) - h;
      out[a] = std::max(d, 0.0);
      inside = std::max(inside, d);
    }
    return len(out) + std::min(inside, 0.0);
  }
  double eval(const Node& n, const D3& p) const {
    if (n.prim >= 0) return primDistance(n.prim, p);
    double r = eval(n.kids[0], p);
    for (size_t k = 1; k < n.kids.size(); ++k) {
      double c = eval(n.kids[k], p);
      r = n.op == CsgOp::kUnion ? std::min(r, c)
                                : n.op == CsgOp::kIntersection ? std::max(r, c) : std::max(r, -c);
    }
    return r;
  }
  /// Every boundary of every primitive along the world line o + t d (double, whole line).
  void boundaries(const D3& o, const D3& d, std::vector<double>& ts) const {
    ts.clear();
    for (const Prim& q : prims) {
      D3 lo = q.toLocal.point(o), ld = q.toLocal.vec(d);
      if (q.sphere) {
        double a = dot(ld, ld), b = dot(lo, ld), c = dot(lo, lo) - q.radius * q.radius;
        double disc = b * b - a * c;
        if (disc < 0) continue;
        ts.push_back((-b - std::sqrt(disc)) / a);
        ts.push_back((-b + std::sqrt(disc)) / a);
        continue;
      }
      double t0 = -1e300, t1 = 1e300;
      for (int ax = 0; ax < 3; ++ax) {
        if (ld[ax] == 0) {
          if (lo[ax] < q.lo[ax] || lo[ax] > q.hi[ax]) t0 = 1, t1 = 0;
          continue;
        }
        double a = (q.lo[ax] - lo[ax]) / ld[ax], b = (q.hi[ax] - lo[ax]) / ld[ax];
        t0 = std::max(t0, std::min(a, b));
        t1 = std::min(t1, std::max(a, b));
      }
      if (t0 <= t1) ts.push_back(t0), ts.push_back(t1);
    }
    std::sort(ts.begin(), ts.end());
  }
};

/// Half extent and centre on the 1/8 grid.
inline void gridBox(Rng& rng, float& c, float& h) {
  h = rng.grid(0.25f, 0.875f);
  c = rng.grid(-0.5f, 0.5f);
}

inline Node makeNode(Rng& rng, Tree& tree, int depth, const DAffine& toWorld,
              std::vector<CsgChild>& siblings) {
  Node n;
  if (depth == 0) {
    Prim p;
    int kind = rng.below(10);
    Mat4 local = Mat4::identity();
    std::shared_ptr<const Shape> shape;
    if (kind < 7) {  // axis-aligned box, placed one of two ways (different rounding paths)
      Vec3 c, h;
      for (int a = 0; a < 3; ++a) gridBox(rng, c[a], h[a]);
      if (kind < 4) {
        shape = std::make_shared<Box>(c - h, c + h);
        p.lo = d3(c - h), p.hi = d3(c + h);
      } else {
        shape = std::make_shared<Box>(-h, h);
        local = Mat4::translate(c);
        p.lo = d3(-h), p.hi = d3(h);
      }
    } else if (kind < 9) {  // rotated box
      Vec3 c, h;
      for (int a = 0; a < 3; ++a) gridBox(rng, c[a], h[a]);
      D3 q = unit({{rng.range(-1, 1), rng.range(-1, 1), rng.range(-1, 1)}});
      double angle = rng.range(0.2, 1.2);
      local = Mat4::translate(c) *
              Mat4::rotate(float(q[0] * std::sin(angle / 2)), float(q[1] * std::sin(angle / 2)),
                           float(q[2] * std::sin(angle / 2)), float(std::cos(angle / 2)));
      shape = std::make_shared<Box>(-h, h);
      p.lo = d3(-h), p.hi = d3(h);
    } else {  // sphere
      Vec3 c{rng.grid(-0.5f, 0.5f), rng.grid(-0.5f, 0.5f), rng.grid(-0.5f, 0.5f)};
      float r = rng.grid(0.5f, 1.0f);
      shape = std::make_shared<Sphere>(r);
      local = Mat4::translate(c);
      p.sphere = true;
      p.radius = r;
    }
    p.toWorld = toWorld * DAffine::of(local);
    p.toLocal = inverse(p.toWorld);
    n.prim = int(tree.prims.size());
    tree.prims.push_back(p);
    siblings.push_back({shape, Transform(local), -1, "leaf"});
    return n;
  }
  n.op = CsgOp(rng.below(3));
  int count = 2 + rng.below(2);
  // A sub-tree is shifted by a grid step sometimes: its faces stay on the grid.
  Mat4 local = rng.below(2) ? Mat4::identity()
                            : Mat4::translate({rng.grid(-0.25f, 0.25f), rng.grid(-0.25f, 0.25f), 0});
  DAffine here = toWorld * DAffine::of(local);
  std::vector<CsgChild> kids;
  for (int k = 0; k < count; ++k)
    n.kids.push_back(makeNode(rng, tree, rng.below(depth), here, kids));
  siblings.push_back(
      {std::make_shared<Csg>(n.op, std::move(kids)), Transform(local), -1, "node"});
  return n;
}

inline Tree makeTree(uint32_t seed) {
  Rng rng(seed);
  Tree tree;
  // The solid at a generic orientation and position in the world.
  D3 axis = unit({{rng.range(-1, 1), rng.range(-1, 1), rng.range(-1, 1)}});
  double angle = rng.range(0.3, 2.8);
  float s = float(std::sin(angle / 2));
  tree.place = Mat4::translate({float(rng.range(-0.3, 0.3)), float(rng.range(-0.3, 0.3)),
                                float(rng.range(-0.3, 0.3))}) *
               Mat4::rotate(float(axis[0]) * s, float(axis[1]) * s, float(axis[2]) * s,
                            float(std::cos(angle / 2)));
  std::vector<CsgChild> top;
  int depth = 1 + rng.below(3);
  tree.root = makeNode(rng, tree, depth, DAffine::of(tree.place), top);
  tree.csg = top[0].shape;
  // The root's own shift is part of its child transform: fold it into the placement.
  tree.place = tree.place * top[0].toCsg.m;
  return tree;
}

}  // namespace tray::test::csg_tree
