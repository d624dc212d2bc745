#include "render/prepared_scene.h"

#include "accel/registry.h"
#include "integrators/registry.h"

namespace tray {

PreparedScene::PreparedScene(const Scene& scene, const CameraDesc& camera, ImageSize size,
                             const std::string& accelerator)
    : scene_(&scene),
      cameraDesc_(camera),
      size_(size),
      camera_(Camera::create(camera, size.width, size.height)),
      ownedAccel_(makeAccelerator(accelerator, scene)),
      accel_(ownedAccel_.get()) {}

PreparedScene::PreparedScene(const Scene& scene, const CameraDesc& camera, ImageSize size,
                             const Accelerator& accelerator)
    : scene_(&scene),
      cameraDesc_(camera),
      size_(size),
      camera_(Camera::create(camera, size.width, size.height)),
      accel_(&accelerator) {}

PreparedScene::PreparedScene(const Scene& scene, ImageSize size, std::unique_ptr<Camera> camera,
                             std::unique_ptr<Accelerator> accelerator)
    : scene_(&scene),
      size_(size),
      camera_(std::move(camera)),
      ownedAccel_(std::move(accelerator)),
      accel_(ownedAccel_.get()) {}

PreparedScene::PreparedScene(std::unique_ptr<Scene> scene, const CameraDesc& cameraDesc,
                             ImageSize size, std::unique_ptr<Camera> camera,
                             std::unique_ptr<Accelerator> accelerator)
    : owned_(std::move(scene)),
      scene_(owned_.get()),
      cameraDesc_(cameraDesc),
      size_(size),
      camera_(std::move(camera)),
      ownedAccel_(std::move(accelerator)),
      accel_(ownedAccel_.get()) {}

RenderContext PreparedScene::context(const RenderSettings& settings) const {
  return context(settings, *accel_);
}

RenderContext PreparedScene::context(const RenderSettings& settings,
                                     const Accelerator& accelerator) const {
  return RenderContext{*scene_, accelerator, *camera_, settings, size_.width, size_.height};
}

std::unique_ptr<Integrator> PreparedScene::integrator(const RenderSettings& settings) const {
  return makeIntegrator(context(settings));
}

Film PreparedScene::render(const RenderSettings& settings, const RenderOptions& options,
                           RenderStats* stats) const {
  const auto made = integrator(settings);
  Film film(size_.width, size_.height);
  const RenderStats st = renderImage(*made, film, options);
  if (stats) *stats = st;
  return film;
}

}  // namespace tray
