#pragma once
// glTF 2.0 scene loading: the only entry point from the file system into a tray::Scene.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/scene.h"
#include "io/memory_estimate.h"

namespace tray {

struct LoadOptions {
  int scene = -1;  ///< glTF scene to load; -1: the file's default `scene` (or 0)
  /// Let buffer and image URIs leave the scene's folder (absolute paths, `..`). Off by default
  /// because scene files come from untrusted sources (docs/scene-format.md, "Validation").
  bool allowAnyPath = false;
  /// Animation time in seconds (glTF 2.0 §3.11): animated values replace the nodes' own. Absent:
  /// the static pose (node TRS, default morph weights, skins at rest), as files render unanimated.
  std::optional<float> time;
  /// Which animation plays at `time`: "first" (the file's first, as glTF viewers play it),
  /// "all" (together), an index or a name.
  std::string animation = "first";
  /// KHR_materials_variants: "none" (each primitive's own material), a variant's name or index.
  std::string variant = "none";
  /// Motion blur (docs/scene-format.md, "Motion blur"), with a `time` only: the shutter in
  /// seconds and the number of times (>= 2, evenly spaced over it) the animation is posed at.
  /// Moving objects get Primitive::motion, deforming meshes positionSteps; 0 steps: none.
  float shutterOpen = 0, shutterClose = 0;
  int motionSteps = 0;
  /// Motion vectors (--aov motion), with a `time` only: the previous frame's time (time -
  /// 1/fps), at which every primitive's and camera's placement is also posed
  /// (Scene::previousToWorld, CameraDesc::previousToWorld).
  std::optional<float> previousTime;
  /// tray-render --max-memory in bytes (0: no limit): a scene whose buffers, textures and
  /// geometry need more is refused before they are allocated (io/memory_estimate.h).
  uint64_t maxMemoryBytes = 0;
  /// The texture tile budget, stored in Scene::textureCacheMB (0: TRay's default).
  double textureCacheMB = 0;
  /// Render even if extensionsRequired names an extension TRay lacks (a warning instead of the
  /// error): the picture may then be wrong, e.g. missing geometry or materials.
  bool ignoreRequiredExtensions = false;
  /// Geometry, cameras and lights only: no texture or environment image is bound (for bounds,
  /// e.g. the automatic camera's sweep over an animation, render/auto_framing.h).
  bool geometryOnly = false;
  /// EXT_mesh_gpu_instancing sets of at least this many instances load as instance arrays
  /// (gltf/gltf_scene_graph.h, kInstanceArrayMinInstances); 0: never (one Primitive each).
  size_t instanceArrayMin = kInstanceArrayMinInstances;
};

struct LoadReport {
  std::vector<std::string> warnings;  ///< one line each, "PATH: message"
  MemoryEstimate memory;              ///< buffers and textures; geometry is main's to add
};

/// Loads a .gltf (with embedded data: URIs or external files) or .glb into a finalized Scene.
/// The whole document is validated first, including parts the chosen scene does not use.
/// Throws tray::Error with a one-line message "PATH: problem" on any bad input; never crashes
/// on malformed files. Warnings (skipped line primitives, dropped degenerate triangles, unknown
/// optional extensions) go to `report` when given.
Scene loadGltf(const std::string& path, const LoadOptions& options = {},
               LoadReport* report = nullptr);

/// A file parsed and checked once, converted into a Scene as often as asked: `--frames` poses
/// each frame from it instead of reading the file again. Parsing reads and checks the file,
/// its buffers and its image bytes (options.allowAnyPath, maxMemoryBytes and
/// ignoreRequiredExtensions apply); scene(options) then converts it with options.time,
/// animation and scene, exactly as loadGltf would.
class GltfDocument {
 public:
  GltfDocument(const std::string& path, const LoadOptions& options, LoadReport* report = nullptr);
  ~GltfDocument();
  GltfDocument(const GltfDocument&) = delete;
  GltfDocument& operator=(const GltfDocument&) = delete;
  Scene scene(const LoadOptions& options, LoadReport* report = nullptr) const;
  /// The first and last keyframe times of the animation options.animation names (of all of
  /// them for "all"); none when the file has no animation.
  std::optional<std::pair<float, float>> animationRange(const LoadOptions& options) const;

 private:
  struct Parsed;
  std::unique_ptr<Parsed> parsed_;
};

/// The same for a document already in memory (.gltf JSON or .glb, told apart by the GLB magic),
/// e.g. for the fuzzer (fuzz/gltf_loader_fuzz.cpp). Only data: URIs and a GLB's BIN chunk can
/// supply buffers and images: any external URI is refused, whatever options.allowAnyPath says.
/// `name` stands for the file in messages.
Scene loadGltfFromMemory(const unsigned char* data, size_t size, const std::string& name,
                         const LoadOptions& options = {}, LoadReport* report = nullptr);

}  // namespace tray
