// shape_bench: "model no more than a scene needs", measured (issue 41). For the torus and each
// capped quadric, the analytic shape against its tessellation at a given silhouette error (the
// largest distance between the surface and its inscribed mesh): triangles, memory (geometry +
// accelerator), accelerator build time, and the time to trace the same camera and bounce rays
// (Embree, one thread), plus the fraction of camera rays whose hit or miss differs; with
// --images, the image each makes (path, one thread) against a converged render of the
// analytic shape: what the tessellation costs in the picture. Prints Markdown tables
// (docs/shapes.md) and, with --csv, the rows for tools/plot_shapes.py. Figures only.
//
//   shape_bench [--size N] [--images SPP] [--csv FILE]   (camera rays: N x N, default 512)
#include <tbb/global_control.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <algorithm>
#include <memory>
#include <optional>
#include <string>

#include "accel/registry.h"
#include "bench/bench_rays.h"
#include "bench/cpu_time.h"
#include "shapes/quadric.h"
#include "shapes/torus.h"
#include "tests/render_film.h"
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
  double renderSeconds = 0, rmse = -1;  ///< --images: the render's CPU time, its RMSE
};

/// Vertex normals of the analytic surface, as an exporter writes them for a smooth mesh (a
/// mesh without them shades flat, which no asset of a torus would): the torus' from its ring,
/// a quadric's from the gradient of x^2 + z^2 - rho^2(y); cap fans get vertices of their own
/// with the cap's normal.
void addSurfaceNormals(TriangleMesh& m, const Shape& shape) {
  if (auto* t = dynamic_cast<const Torus*>(&shape)) {
    for (const Vec3& p : m.positions) {
      const Vec3 ring = t->majorRadius() * normalize(Vec3(p.x, 0.0f, p.z));
      m.normals.push_back(normalize(p - ring));
    }
    return;
  }
  const auto& q = static_cast<const Quadric&>(shape);
  const size_t side = m.positions.size() - (q.capped() ? 2 : 0);  // the fans' centres last
  // revolvedMesh's layout: vertex k is at azimuth 2 pi (k mod nu) / nu. Divided by 2 rho the
  // gradient is (sin phi, -d rho / dy, cos phi), which holds at an apex too (a cone's, where
  // each generator keeps its own normal, as an exporter splits the apex), unlike the gradient.
  const size_t nu = q.kind() == Quadric::Kind::kCylinder || q.kind() == Quadric::Kind::kCone
                        ? side / 2
                        : 0;
  for (size_t k = 0; k < side; ++k) {
    const Vec3 p = m.positions[k];
    const double h = 1e-4 * q.height(), y = std::clamp<double>(p.y, h, q.height() - h);
    const double slope = (q.rho2(y + h) - q.rho2(y - h)) / (2 * h);  // d rho^2 / dy
    const double rho = std::sqrt(std::max(0.0, q.rho2(y)));
    Vec3 n(2 * p.x, float(-slope), 2 * p.z);
    if (nu && rho > 1e-6) {
      const double phi = 2 * M_PI * double(k % nu) / double(nu);
      n = Vec3(float(std::sin(phi)), float(-slope / (2 * rho)), float(std::cos(phi)));
    }
    m.normals.push_back(length(n) > 0 ? normalize(n) : Vec3(0, p.y > 0 ? 1.0f : -1.0f, 0));
  }
  for (size_t k = side; k < m.positions.size(); ++k)
    m.normals.push_back(Vec3(0, m.positions[k].y > 0 ? 1.0f : -1.0f, 0));
  // Each fan triangle (centre, rim, rim): its rim vertices copied with the cap's normal.
  for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
    const uint32_t centre = m.indices[t];
    if (centre < side) continue;  // a side triangle
    for (size_t c = 1; c < 3; ++c) {
      m.positions.push_back(m.positions[m.indices[t + c]]);
      m.normals.push_back(m.normals[centre]);
      m.indices[t + c] = uint32_t(m.positions.size() - 1);
    }
  }
}

/// The shapes' scene for images: a grey Lambertian under a point light and a dim sky.
void light(Scene& s) {
  s.lights.push_back(test::pointLight(Vec3(3, 4, 5), Color(60.0f)));
  s.environment.ambient = Color(0.2f);
  s.environment.background = Color(0.2f);
}

constexpr int kImageSize = 96;

Film renderImage(const Scene& scene, int spp, int seed, double* cpu) {
  RenderSettings settings;
  settings.set("integrator", "path");
  settings.set("spp", spp);
  settings.set("seed", seed);
  settings.set("max-depth", 4);
  const CameraDesc cam = Camera::framing(scene.bounds(), 1.0f);
  const double c0 = cpuSeconds();
  Film f = test::renderFilm(scene, cam, kImageSize, kImageSize, settings, nullptr, {}, "embree", 1);
  if (cpu) *cpu = cpuSeconds() - c0;
  return f;
}

double rmse(const Film& a, const Film& b) {
  double sum = 0;
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x)
      for (int c = 0; c < 3; ++c) {
        const double d = a.pixel(Film::kBeauty, x, y)[c] - b.pixel(Film::kBeauty, x, y)[c];
        sum += d * d;
      }
  return std::sqrt(sum / (3.0 * a.width() * a.height()));
}

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

std::vector<std::pair<std::string, Measure>> gRows;  // for the --images table and --csv

void row(const char* name, const char* model, const Measure& m) {
  std::printf("| %s | %s | %zu | %.1f | %.2f | %.2f | %.2f | %.4f%% |\n", name, model, m.triangles,
              double(m.bytes) / 1024.0, m.buildMs, m.camMrays, m.bounceMrays, 100 * m.differ);
  gRows.push_back({std::string(name) + "\t" + model, m});
}

}  // namespace

int main(int argc, char** argv) {
  int size = 512, imageSpp = 0;
  const char* csv = nullptr;
  for (int i = 1; i + 1 < argc; ++i) {
    if (!std::strcmp(argv[i], "--size")) size = std::atoi(argv[i + 1]);
    if (!std::strcmp(argv[i], "--images")) imageSpp = std::atoi(argv[i + 1]);
    if (!std::strcmp(argv[i], "--csv")) csv = argv[i + 1];
  }
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
    // The converged reference: the analytic shape at 16x the spp, another seed.
    std::optional<Film> converged;
    if (imageSpp > 0) {
      Scene lit = a;
      light(lit);
      converged = renderImage(lit, 16 * imageSpp, 1, nullptr);
      ma.rmse = rmse(renderImage(lit, imageSpp, 0, &ma.renderSeconds), *converged);
    }
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
      TriangleMesh smooth = mesh;  // for the image: with the normals an exporter writes
      test::addMeshInstance(m, test::addMesh(m, std::move(mesh)), Mat4::identity());
      m.finalize();
      Measure mm = measure(m, rays, bytes, &reference, nullptr);
      mm.triangles = tris;
      if (converged) {
        addSurfaceNormals(smooth, *c.shape);
        Scene lit;
        test::addMaterial(lit, test::diffuse(Color(0.5f)));
        test::addMeshInstance(lit, test::addMesh(lit, std::move(smooth)), Mat4::identity());
        light(lit);
        lit.finalize();
        mm.rmse = rmse(renderImage(lit, imageSpp, 0, &mm.renderSeconds), *converged);
      }
      char model[64];
      std::snprintf(model, sizeof model, "mesh, error %g", eps);
      row(c.name, model, mm);
    }
  }
  if (imageSpp > 0) {
    std::printf("\nImages: %dx%d, path (max depth 4), %d spp, one thread, against the analytic "
                "shape at %d spp (another seed); the analytic row's RMSE is the noise floor.\n\n"
                "| shape | model | render CPU s | RMSE |\n|---|---|---|---|\n",
                kImageSize, kImageSize, imageSpp, 16 * imageSpp);
    for (const auto& [key, m] : gRows) {
      if (m.rmse < 0) continue;
      std::string cells = key;
      cells.replace(cells.find('\t'), 1, " | ");
      std::printf("| %s | %.3f | %.5f |\n", cells.c_str(), m.renderSeconds, m.rmse);
    }
  }
  if (csv) {
    FILE* f = std::fopen(csv, "w");
    if (!f) return 1;
    std::fprintf(f, "shape\tmodel\ttriangles\tbytes\tbuild_ms\tcamera_mrays\tbounce_mrays\t"
                    "differing\trender_s\trmse\n");
    for (const auto& [key, m] : gRows)
      std::fprintf(f, "%s\t%zu\t%zu\t%.4f\t%.4f\t%.4f\t%.6f\t%.4f\t%.6f\n", key.c_str(),
                   m.triangles, m.bytes, m.buildMs, m.camMrays, m.bounceMrays, m.differ,
                   m.renderSeconds, m.rmse);
    std::fclose(f);
  }
  return 0;
}
