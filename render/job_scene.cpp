#include "render/job_scene.h"

#include <algorithm>
#include <cstdio>
#include <optional>

#include "accel/registry.h"
#include "integrators/registry.h"
#include "io/environment_map.h"
#include "io/memory_estimate.h"
#include "render/auto_framing.h"
#include "render/ray_range.h"
#include "render/render_setup.h"

namespace tray {
namespace {

/// The scene as read, with --env applied; the loader's warnings reported.
std::unique_ptr<Scene> loadScene(const RenderJob& job, const LoadOptions& loadOptions,
                                 const GltfDocument* document, LoadReport& report,
                                 const RenderJobEvents& events) {
  auto scene = std::make_unique<Scene>(document ? document->scene(loadOptions, &report)
                                                : loadGltf(job.scene.path, loadOptions, &report));
  scene->sourcePath = job.scene.path;
  // --env: read and checked (its size against --max-memory before decoding).
  applyEnvironmentOptions(*scene, job.settings, &report.warnings, loadOptions.maxMemoryBytes);
  // The map (--env's or TRAY_environment's) counts in the one budget with the rest.
  if (const auto& map = scene->environment.map)
    report.memory.environment = environmentMapBytes(map->width, map->height);
  for (const auto& w : report.warnings) warn(events, w);
  return scene;
}

/// The placed camera, else one framing the scene: at a --time of an animated file, its bounds
/// over the whole animation (render/auto_framing.h), so every frame is framed alike.
CameraDesc jobCamera(const RenderJob& job, const Scene& scene, int placedCamera,
                     const LoadOptions& loadOptions, const GltfDocument* document) {
  if (placedCamera >= 0) return scene.cameras[size_t(placedCamera)];
  std::optional<Bounds3> swept;
  if (loadOptions.time) {
    swept = job.framingBounds;
    if (!swept) {
      std::optional<GltfDocument> own;  // a still at a --time: the file is read once more
      if (!document) document = &own.emplace(job.scene.path, loadOptions);
      swept = sweptFramingBounds(job, *document);
    }
  }
  // The sweep alone, not widened by this frame's bounds: every frame gets the same camera.
  return Camera::framing(swept ? *swept : scene.bounds(), 4.0f / 3.0f);
}

/// Adds TRay's default lighting when the scene is unlit (and --no-default-light is not set);
/// returns whether it did.
bool lightUnlitScene(const RenderJob& job, Scene& scene, const CameraDesc& camera) {
  // --no-default-light: nothing added; an unlit asset renders black (or lit by weak emitters).
  if (job.settings.getBool("no-default-light")) return false;
  return addDefaultLightingIfUnlit(scene, camera);
}

/// Once the accelerator exists: an unlit sky box around the camera takes the default light's
/// place, or a headlight replaces the key light that an enclosure keeps out; each said once.
void placeDefaultLight(const RenderJob& job, Scene& scene, const CameraDesc& camera,
                       const Accelerator& accel, const RenderJobEvents& events) {
  if (unlitSurfacesLight(job.settings) && useUnlitEnclosureAsLight(scene, camera, accel)) {
    warn(events, job.scene.path +
                     " has no lights of meaningful power, and the camera is inside unlit "
                     "geometry (a sky box or dome): it lights the scene as the sky it stands for");
    return;
  }
  warn(events, job.scene.path +
                   " has no lights of meaningful power: using TRay's default headlight and a 0.1 "
                   "environment (docs/scene-format.md; --no-default-light turns it off)");
  if (useHeadlightIfEnclosed(scene, camera, accel))
    warn(events, job.scene.path +
                     ": the camera is enclosed (a sky box?) and the default key light cannot get "
                     "in: a headlight at the camera replaces it");
}

/// Refuses a scene whose accelerator would not fit, before it is built: the loader's estimate
/// and the geometry (a deforming mesh: its triangles at every motion step).
void checkAcceleratorMemory(const RenderJob& job, const Scene& scene, MemoryEstimate need,
                            uint64_t limitBytes) {
  for (const auto& m : scene.meshes)
    need.geometry += m.triangleCount() * std::max<size_t>(1, m.positionSteps.size());
  need.geometry *= kGeometryBytesPerTriangle;
  for (const Primitive& p : scene.primitives)  // instances cost too
    need.geometry +=
        p.instances ? p.instances->size() * kBytesPerArrayInstance : kBytesPerPlacement;
  checkMemory(job.scene.path, need, limitBytes);
}

}  // namespace

void warn(const RenderJobEvents& events, const std::string& message) {
  if (events.warning)
    events.warning(message);
  else
    std::fprintf(stderr, "warning: %s\n", message.c_str());
}

void enterPhase(const RenderJobEvents& events, const char* phase) {
  if (events.phase) events.phase(phase);
}

PreparedScene prepareJobScene(const RenderJob& job, const RenderJobEvents& events,
                              const GltfDocument* document, int& placedCamera, KeptScene* kept) {
  if (kept && kept->scene) {  // loaded, lit and built by an earlier render: its camera now
    placedCamera = kept->placedCamera;
    CameraDesc cameraDesc = kept->camera;
    applyLensOptions(cameraDesc, job.settings);
    checkRayRange(job.scene.path, *kept->scene, cameraDesc);
    return PreparedScene(*kept->scene, cameraDesc, resolveImageSize(job.resolution, cameraDesc),
                         *kept->accelerator);
  }
  enterPhase(events, "loading the scene");
  const LoadOptions loadOptions = loadOptionsOf(job);
  LoadReport report;
  std::unique_ptr<Scene> scene = loadScene(job, loadOptions, document, report, events);

  placedCamera = findCamera(*scene, job.camera);
  const CameraDesc chosen = jobCamera(job, *scene, placedCamera, loadOptions, document);
  CameraDesc cameraDesc = chosen;
  applyLensOptions(cameraDesc, job.settings);
  checkRayRange(job.scene.path, *scene, cameraDesc);  // before anything is built or traced
  const bool defaultLight = lightUnlitScene(job, *scene, cameraDesc);
  const ImageSize size = resolveImageSize(job.resolution, cameraDesc);
  auto camera = Camera::create(cameraDesc, size.width, size.height);
  checkAcceleratorMemory(job, *scene, report.memory, loadOptions.maxMemoryBytes);

  enterPhase(events, "building the accelerator");
  auto accel = makeAccelerator(job.accelerator, *scene);
  if (defaultLight)
    placeDefaultLight(job, *scene, cameraDesc, *accel, events);
  else if (scene->environment.map && cameraEnclosed(cameraDesc, *accel)) {
    warn(events, job.scene.path +
                     ": the camera is enclosed (a sky box or a room): the environment map "
                     "lights only what its light reaches through openings; nothing of it is "
                     "seen");
  }
  if (kept) {
    kept->camera = chosen;
    kept->placedCamera = placedCamera;
    kept->headlight = defaultLight;
    kept->scene = std::move(scene);
    kept->accelerator = std::move(accel);
    return PreparedScene(*kept->scene, cameraDesc, size, *kept->accelerator);
  }
  return PreparedScene(std::move(scene), cameraDesc, size, std::move(camera), std::move(accel));
}

}  // namespace tray
