#pragma once
// A scene made ready to render: its camera, image size and accelerator, kept alive together, and
// the RenderContext every integrator is made from. The job (render/render_job.h) loads and
// lights a scene into one; tests and benchmarks build one from a Scene made in code.
#include <memory>
#include <string>

#include "core/accelerator.h"
#include "core/camera.h"
#include "core/integrator.h"
#include "core/scene.h"
#include "film/film.h"
#include "film/render_state.h"
#include "render/render_setup.h"
#include "render/renderer.h"

namespace tray {

class PreparedScene {
 public:
  /// Borrows `scene`, which must outlive this; makes the camera for `size` and builds the
  /// accelerator named (accel/registry.h).
  PreparedScene(const Scene& scene, const CameraDesc& camera, ImageSize size,
                const std::string& accelerator = "embree");
  /// Borrows `scene` and an accelerator already built over it (benchmarks render one scene at
  /// several image sizes).
  PreparedScene(const Scene& scene, const CameraDesc& camera, ImageSize size,
                const Accelerator& accelerator);
  /// Borrows `scene` with a camera and an accelerator of the caller's (test stand-ins).
  PreparedScene(const Scene& scene, ImageSize size, std::unique_ptr<Camera> camera,
                std::unique_ptr<Accelerator> accelerator);
  /// Owns `scene` (the job's, as loaded), its camera and the accelerator built over it.
  PreparedScene(std::unique_ptr<Scene> scene, const CameraDesc& cameraDesc, ImageSize size,
                std::unique_ptr<Camera> camera, std::unique_ptr<Accelerator> accelerator);

  const Scene& scene() const { return *scene_; }
  const CameraDesc& cameraDesc() const { return cameraDesc_; }
  const Camera& camera() const { return *camera_; }
  const Accelerator& accelerator() const { return *accel_; }
  int width() const { return size_.width; }
  int height() const { return size_.height; }

  /// What an integrator made for this scene with `settings` sees.
  RenderContext context(const RenderSettings& settings) const;
  /// The same with another accelerator over this scene (a wrapper that counts or times calls).
  RenderContext context(const RenderSettings& settings, const Accelerator& accelerator) const;
  /// The integrator `settings` name ("integrator"), from the registry.
  std::unique_ptr<Integrator> integrator(const RenderSettings& settings) const;

  /// Renders the whole image with the settings' integrator: the short form for scenes in code.
  /// `stats`, when not null, receives the render's counters.
  Film render(const RenderSettings& settings, const RenderOptions& options = {},
              RenderStats* stats = nullptr) const;

 private:
  std::unique_ptr<Scene> owned_;  ///< null when the scene is borrowed
  const Scene* scene_;
  CameraDesc cameraDesc_;
  ImageSize size_;
  std::unique_ptr<Camera> camera_;
  std::unique_ptr<Accelerator> ownedAccel_;  ///< null when the accelerator is borrowed
  const Accelerator* accel_;
};

}  // namespace tray
