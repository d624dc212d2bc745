// shape_bench: "model no more than a scene needs", measured (issue 41). For the torus and each
// capped quadric, the analytic shape against its tessellation at a given silhouette error (the
// largest distance between the surface and its inscribed mesh): triangles, memory (geometry +
// accelerator), accelerator build time, and the time to trace the same camera and bounce rays
// (Embree, one thread), plus the fraction of camera rays whose hit or miss differs.
// Prints a Markdown table (docs/shapes.md). Not a test: figures only.
//
//   shape_bench [--size N]   (camera rays: N x N, default 512)
#include <tbb/global_control.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>

#include "accel/registry.h"
#include "bench/bench_rays.h"
#include "bench/cpu_time.h"
#include "shapes/quadric.h"
#include "shapes/torus.h"
#include "tests/scene_builder.h"
#include "tests/shapes/solid_meshes.h"

using namespace tray;
using Clock = std::chrono::steady_clock;

namespace {

/// Segments of a circle of radius rho whose chords stay within eps of it.
int segments(double rho, double eps) {
  return std::max(3, int(std::ceil(M_PI / std::acos(std::max(-1.0, 1 - eps / rho)))));
}

/// Rows along y for the quadric's profile within eps (profile polyline vs the curve, sampled).
int rows(const Quadric& q, double eps) {
  if (q.kind() == Quadric::Kind::kCylinder || q.kind() == Quadric::Kind::kCone) return 1;
  for (int nv = 1;; nv = std::max(nv + 1, int(nv * 1.2))) {
    double worst = 0;
    auto yAt = [&](double w) {
      return q.height() * (q.kind() == Quadric::Kind::kParaboloid ? w * w : w);
    };
    for (int j = 0; j < nv; ++j) {
      double y0 = yAt(double(j) / nv), y1 = yAt(double(j + 1) / nv);
      double r0 = std::sqrt(std::max(0.0, q.rho2(y0))), r1 = std::sqrt(std::max(0.0, q.rho2(y1)));
      double ly = y1 - y0, lr = r1 - r0, l = std::hypot(ly, lr);
      for (int k = 1; k < 16; ++k) {  // distance of profile points to the chord
        double y = y0 + (y1 - y0) * k / 16, r = std::sqrt(std::max(0.0, q.rho2(y)));
        worst = std::max(worst, std::fabs((y - y0) * lr - (r - r0) * ly) / l);
      }
    }
    if (worst <= eps) return nv;
  }
}

struct Measure {
  size_t triangles = 0, bytes = 0;
  double buildMs = 0, camMrays = 0, bounceMrays = 0;
  double differ = 0;  ///< fraction of camera rays whose hit / miss differs from the analytic
};

/// Best of kRepeats: builds and traces are short (milliseconds), so the minimum is the figure
/// least disturbed by whatever else runs on the machine.
constexpr int kRepeats = 5;

Measure measure(const Scene& scene, const bench::RaySet& rays, size_t geometryBytes,
                const std::vector<uint8_t>* reference, std::vector<uint8_t>* hitsOut) {
  Measure m;
  m.buildMs = 1e30;
  std::unique_ptr<Accelerator> accel;
  for (int k = 0; k < kRepeats; ++k) {
    accel.reset();
    const auto t0 = Clock::now();
    accel = makeAccelerator("embree", scene);
    m.buildMs =
        std::min(m.buildMs, std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
  }
  m.bytes = geometryBytes + accel->memoryBytes();
  std::vector<uint8_t> hits(rays.camera.size());
  double camera = 1e30, bounce = 1e30;
  for (int k = 0; k < kRepeats; ++k) {
    const double c0 = cpuSeconds();
    for (size_t i = 0; i < rays.camera.size(); ++i) {
      Hit h;
      hits[i] = accel->intersect(rays.camera[i], h);
    }
    const double c1 = cpuSeconds();
    for (const Ray& r : rays.bounce) {
      Hit h;
      accel->intersect(r, h);
    }
    const double c2 = cpuSeconds();
    camera = std::min(camera, c1 - c0), bounce = std::min(bounce, c2 - c1);
  }
  m.camMrays = double(rays.camera.size()) / std::max(1e-9, camera) * 1e-6;
  m.bounceMrays = double(rays.bounce.size()) / std::max(1e-9, bounce) * 1e-6;
  if (reference) {
    size_t d = 0;
    for (size_t i = 0; i < hits.size(); ++i) d += hits[i] != (*reference)[i];
    m.differ = double(d) / double(hits.size());
  }
  if (hitsOut) *hitsOut = std::move(hits);
  return m;
}

void row(const char* name, const char* model, const Measure& m) {
  std::printf("| %s | %s | %zu | %.1f | %.2f | %.2f | %.2f | %.4f%% |\n", name, model, m.triangles,
              double(m.bytes) / 1024.0, m.buildMs, m.camMrays, m.bounceMrays, 100 * m.differ);
}

}  // namespace

int main(int argc, char** argv) {
  int size = 512;
  for (int i = 1; i + 1 < argc; ++i)
    if (!std::strcmp(argv[i], "--size")) size = std::atoi(argv[i + 1]);
  tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
  struct Case {
    const char* name;
    std::shared_ptr<const Shape> shape;
  };
  const std::vector<Case> cases = {
      {"torus (R 1, r 0.25)", std::make_shared<Torus>(1.0f, 0.25f)},
      {"cylinder (r 0.5, h 1.5, capped)",
       std::make_shared<Quadric>(Quadric::Kind::kCylinder, 0.5f, 1.5f, true)},
      {"cone (r 0.5, h 1.5, capped)",
       std::make_shared<Quadric>(Quadric::Kind::kCone, 0.5f, 1.5f, true)},
      {"paraboloid (r 0.5, h 1.5, capped)",
       std::make_shared<Quadric>(Quadric::Kind::kParaboloid, 0.5f, 1.5f, true)},
      {"hyperboloid (r 0.5, waist 0.25, h 1.5, capped)",
       std::make_shared<Quadric>(Quadric::Kind::kHyperboloid, 0.5f, 1.5f, true, 0.25f)},
  };
  std::printf("Camera rays: %d x %d; Embree, one thread; Mrays/s per CPU second.\n\n", size, size);
  std::printf(
      "| shape | model | triangles | memory KiB | build ms | camera Mrays/s | bounce "
      "Mrays/s | camera rays differing |\n|---|---|---|---|---|---|---|---|\n");
  for (const Case& c : cases) {
    Scene a;
    test::addShape(a, c.shape, Mat4::identity(), test::addMaterial(a, test::diffuse(Color(0.5f))));
    a.finalize();
    const bench::RaySet rays = bench::makeRays(a, size, size);
    std::vector<uint8_t> reference;
    const size_t shapeBytes =
        dynamic_cast<const Torus*>(c.shape.get()) ? sizeof(Torus) : sizeof(Quadric);
    Measure ma = measure(a, rays, shapeBytes, nullptr, &reference);
    row(c.name, "analytic", ma);
    if (auto* t = dynamic_cast<const Torus*>(c.shape.get())) {
      // The same torus with the closed-form solver (polished): what robustness costs.
      Scene cf;
      test::addShape(cf,
                     std::make_shared<Torus>(t->majorRadius(), t->minorRadius(),
                                             QuarticSolver::kClosedFormPolished),
                     Mat4::identity(), test::addMaterial(cf, test::diffuse(Color(0.5f))));
      cf.finalize();
      row(c.name, "analytic, closed form + Newton (loses hits)",
          measure(cf, rays, shapeBytes, &reference, nullptr));
    }
    for (double eps : {1e-2, 1e-3, 1e-4}) {
      TriangleMesh mesh;
      if (auto* t = dynamic_cast<const Torus*>(c.shape.get())) {
        mesh = test::torusMesh(t->majorRadius(), t->minorRadius(),
                               segments(t->majorRadius() + t->minorRadius(), eps),
                               segments(t->minorRadius(), eps));
      } else {
        auto* q = static_cast<const Quadric*>(c.shape.get());
        mesh = test::revolvedMesh(*q, segments(q->radius(), eps), rows(*q, eps));
      }
      Scene m;
      test::addMaterial(m, test::diffuse(Color(0.5f)));
      const size_t tris = mesh.indices.size() / 3;
      const size_t bytes = mesh.positions.size() * sizeof(Vec3) + mesh.indices.size() * 4;
      test::addMeshInstance(m, test::addMesh(m, std::move(mesh)), Mat4::identity());
      m.finalize();
      Measure mm = measure(m, rays, bytes, &reference, nullptr);
      mm.triangles = tris;
      char model[64];
      std::snprintf(model, sizeof model, "mesh, error %g", eps);
      row(c.name, model, mm);
    }
  }
  return 0;
}
