#pragma once
// The sppm integrator's class (integrators/sppm.h), shared by its three files: the frame loop
// and pixel statistics (sppm.cpp), the camera pass (sppm_camera.cpp) and the photon pass
// (sppm_photons.cpp). Hachisuka & Jensen 2009; the structure of pbrt-v3 16.2.
#include <optional>
#include <span>
#include <vector>

#include "core/integrator.h"
#include "integrators/sppm_grid.h"
#include "integrators/surface_vertex.h"
#include "lights/emission_sampler.h"
#include "lights/light_set.h"
#include "materials/bsdf.h"

namespace tray {

/// A camera path's first non-delta vertex in one iteration (pbrt's VisiblePoint).
struct VisiblePoint {
  Vec3 p, wo;
  Color beta;                ///< the camera path's throughput up to p
  int depth = 0;             ///< camera segments up to p
  std::optional<Bsdf> bsdf;  ///< none: the pixel has no visible point this iteration
};

/// One pixel's statistics over the iterations (Hachisuka & Jensen 2009, sec. 4.2).
struct SppmPixel {
  float radius = 0;   ///< 0 until the pixel's first visible point sets it
  double ld[3] = {};  ///< emission along the camera path and direct light, summed
  Color tau{0.0f};    ///< the flux gathered within the current radius (pbrt's tau)
  float n = 0;        ///< the accumulated photon count N
  uint32_t hits = 0;  ///< camera rays that met something (coverage)
};

/// A photon gathered by visible point vp: what the point's BSDF weighs in the reduction.
struct PhotonHit {
  uint32_t vp;
  Vec3 wi;     ///< towards where the photon came from
  Color beta;  ///< the photon's flux weight
};

class SppmIntegrator final : public Integrator {
 public:
  explicit SppmIntegrator(const RenderContext& ctx);
  Color Li(const Ray&, Sampler&, RayStats&, PrimaryHit*) const override;
  bool rendersFrames() const override { return true; }
  FrameResult renderFrame(const FrameTask& task, std::span<FramePixel> pixels) const override;

 private:
  /// Iteration k's visible point of every pixel of the task (sppm_camera.cpp); adds the
  /// camera paths' emission and direct light to the pixels' ld and sets first radii.
  void cameraPass(const FrameTask& task, int k, std::span<VisiblePoint> vps,
                  std::span<SppmPixel> stats, std::span<FramePixel> pixels, RayStats& rays) const;
  /// One camera path of pixel (x, y) in iteration k: its radiance up to the visible point
  /// `vp`; `seen` receives what the camera ray hit first.
  Color traceCamera(int x, int y, int k, VisiblePoint& vp, SppmPixel& pixel, PrimaryHit& seen,
                    RayStats& rays) const;
  /// Direct light at a visible point by next-event estimation (light sampling alone: the
  /// path ends there, so no BSDF sample can find the light).
  Color directLight(const SurfaceVertex& v, const Bsdf& bsdf, const MediumStack& media,
                    Sampler& sampler, RayStats& rays) const;
  /// The radius a pixel starts with: --sppm-radius, or kFootprints pixel footprints at the
  /// distance `along` the camera path.
  float initialRadius(int x, int y, float along) const;
  /// Iteration k's photons (sppm_photons.cpp): each visible point's gathered flux sum
  /// beta_photon f(wo, wi) in `phi` and count in `m`, summed in photon order.
  void photonPass(int k, std::span<const VisiblePoint> vps, std::span<const SppmPixel> stats,
                  std::span<Color> phi, std::span<uint32_t> m, RayStats& rays) const;
  /// Photon i of iteration k, adding what visible points gather to `out` in order.
  void tracePhoton(int k, uint32_t i, const VisiblePointGrid& grid,
                   std::span<const VisiblePoint> vps, std::vector<PhotonHit>& out,
                   RayStats& rays) const;

  /// Pixel footprints across the automatic initial radius (--sppm-radius 0).
  static constexpr float kFootprints = 2.0f;
  /// Photons traced by one task: the reduction's order does not depend on it.
  static constexpr uint32_t kPhotonChunk = 2048;
  int maxDepth_, iterations_;
  uint32_t photons_;
  float alpha_, radius_;
  uint64_t photonSeed_;
  SurfaceVertices vertices_;
  LightSet lights_;
  EmissionSampler emitter_;
};

}  // namespace tray
