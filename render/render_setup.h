#pragma once
// Choices every front end makes the same way: which camera and what image size.
#include <string>

#include "core/accelerator.h"
#include "core/render_options.h"
#include "core/scene.h"

namespace tray {

/// The placed camera (an index into scene.cameras, which follow node order) that `which`
/// names: "" the default, the one with the lowest glTF camera index (so that it is `--camera
/// 0` whenever the file's cameras[0] is placed; scenes built in code: the first); digits N
/// the file's cameras[N]; anything else a node name or a camera name. A camera placed by
/// several nodes, or a name several share: the first in node order. -1 when `which` is empty
/// and the scene has no camera. Throws tray::Error (one line listing the scene's cameras) for
/// an index or name the scene does not place.
int findCamera(const Scene& scene, const std::string& which);

/// scene.cameras[findCamera(scene, which)], or a camera framing the scene's bounds when it
/// has none.
CameraDesc chooseCamera(const Scene& scene, const std::string& which);
/// The same with an index: -1 the default, N >= 0 the file's cameras[N].
CameraDesc chooseCamera(const Scene& scene, int index);

/// The thin-lens options that were set (--lens-radius, --focus-distance, --aperture-blades)
/// over the camera's own (TRAY_camera); throws tray::Error for 1 or 2 blades.
void applyLensOptions(CameraDesc& camera, const RenderSettings& settings);

struct ImageSize {
  int width = 640, height = 480;
};

/// What a scene's emissive surfaces give off, to decide whether it is lit.
struct EmissionSummary {
  /// Irradiance of the default key light.
  static constexpr float kDefaultIrradiance = 2.5f;
  /// Emitters count as lighting when their power is at least this share of what the default
  /// key light would pour onto the scene (its irradiance over a quarter of the surface area,
  /// a convex body's mean projected area).
  static constexpr double kMeaningfulShare = 0.01;
  double meshPower = 0;    ///< sum over emissive triangles of area x pi L (L: factor x mean texel)
  double surfaceArea = 0;  ///< world area of every mesh triangle
  bool emissiveShapes = false;
  bool meaningful() const;
};
EmissionSummary summarizeEmission(const Scene& scene);

/// A scene with no light of meaningful power (no punctual light, a black TRAY_environment,
/// and emitters too weak to light it: e.g. a mostly black emissive texture) would render black,
/// which is never what a user wants from a glTF asset made for viewers that bring their own
/// light. Adds TRay's default lighting, as a viewer's headlight: a directional key light of
/// irradiance 2.5 arriving from above-left behind the camera, and a uniform environment of
/// 0.1 (ambient and background). Returns whether it did.
bool addDefaultLightingIfUnlit(Scene& scene, const CameraDesc& camera);

/// After addDefaultLightingIfUnlit added its key light (the last of scene.lights): when the
/// camera is enclosed, so that neither that light nor the environment can reach what it sees
/// (a sky box or sky dome around the asset, a closed room), replaces the key light by a
/// headlight that moves with the camera: a point light at the camera, whose intensity E d^2
/// gives the key light's irradiance E at the distance d where the view's centre ray meets the
/// scene. Enclosed means: rays from the camera towards the key light and along the six axes
/// all hit something. Needs the scene's accelerator (built before lights matter). Returns
/// whether it replaced the light.
bool useHeadlightIfEnclosed(Scene& scene, const CameraDesc& camera, const Accelerator& accel);

/// After addDefaultLightingIfUnlit, for an integrator that lights from unlit surfaces
/// (integrators/registry.h unlitSurfacesLight): when every ray of useHeadlightIfEnclosed's test
/// meets a KHR_materials_unlit surface of some colour, the camera is inside geometry the author
/// made to stand for the sky (an unlit textured sky box or dome). That geometry is then the
/// scene's light, as it was the author's: the default key light and 0.1 environment are taken
/// out again, and paths that find the sky carry its colour. Returns whether it did.
bool useUnlitEnclosureAsLight(Scene& scene, const CameraDesc& camera, const Accelerator& accel);

/// Whether rays from the camera along the six axes all meet geometry: an environment map
/// (--env, TRAY_environment) then lights nothing the camera sees.
bool cameraEnclosed(const CameraDesc& camera, const Accelerator& accel);

/// Parses "WxH"; empty: 640 wide with the height from the camera's aspect ratio (4:3 if unset).
ImageSize resolveImageSize(const std::string& text, const CameraDesc& camera);

}  // namespace tray
