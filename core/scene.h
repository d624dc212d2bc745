#pragma once
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/hit.h"
#include "core/instance_array.h"
#include "core/light_desc.h"
#include "core/material.h"
#include "core/transform.h"
#include "core/shape.h"
#include "core/texture_image.h"
#include "core/triangle_mesh.h"

namespace tray {

/// One placed object: a mesh instance or an analytic shape, with its object-to-world transform;
/// or an instance array (`instances` set): a static mesh placed many times, toWorld unused
/// (identity), each instance's placement read through Scene::placement.
struct Primitive {
  enum class Kind { kMesh, kShape };
  Kind kind = Kind::kMesh;
  uint32_t mesh = 0;                   ///< kMesh: index into Scene::meshes
  std::shared_ptr<const Shape> shape;  ///< kShape
  Transform toWorld;                   ///< at the frame's time; what lights and framing use
  /// Motion blur (core/motion.h): toWorld at motion steps evenly spaced over the shutter (ray
  /// time 0 to 1), linearly interpolated in between as Embree's instance motion. Empty: static.
  std::vector<Mat4> motion;
  int material = 0;  ///< kShape: its material (meshes carry their own)
  int objectId = 0;  ///< glTF node index, for AOVs and mattes
  std::string name;
  /// kMesh only: an instance array (core/instance_array.h); shared by the arrays of one node's
  /// mesh primitives. Null: one placement, toWorld.
  std::shared_ptr<const InstanceArray> instances;
  /// How many placements this primitive stands for (Hit::instance runs over 0..count-1).
  size_t instanceCount() const { return instances ? instances->size() : 1; }
};

/// What a layer above core makes once for a scene and keeps with it, type-erased (core does
/// not know the type): the texture sampler with its MIP pyramids (textures/shading.cpp), made
/// by the first render and reused by the next ones of the same scene (tray.Scene renders one
/// scene many times). A copy or move of the scene starts empty: what is kept refers to this
/// scene's own data (its textures), not the copy's.
class SceneCacheSlot {
 public:
  SceneCacheSlot() = default;
  SceneCacheSlot(const SceneCacheSlot&) {}
  SceneCacheSlot& operator=(const SceneCacheSlot&) { return *this; }
  /// The value kept, made by `make` under a lock the first time.
  template <class Make>
  std::shared_ptr<const void> get(Make&& make) const {
    std::lock_guard lock(mutex_);
    if (!value_) value_ = make();
    return value_;
  }

 private:
  mutable std::mutex mutex_;
  mutable std::shared_ptr<const void> value_;
};

/// Everything a render needs, as plain data. Filled by io/ (glTF) or by tests in code; the
/// accelerator is built from it separately (core/accelerator.h).
struct Scene {
  std::string sourcePath;
  std::vector<TriangleMesh> meshes;
  std::vector<Primitive> primitives;
  std::vector<Material> materials;  ///< never empty once finalize() ran
  std::vector<PunctualLightDesc> lights;
  std::vector<CameraDesc> cameras;
  std::vector<TextureImage> textures;
  double textureCacheMB = 0;  ///< texture tile budget (--texture-memory); 0: default
  Environment environment;
  /// The shutter interval in seconds that ray time 0 to 1 spans (docs/scene-format.md,
  /// "Motion blur"); both 0 without --shutter.
  float shutterOpen = 0, shutterClose = 0;
  /// Per primitive: its toWorld one frame before (time - 1/fps), for motion vectors (core/
  /// motion_vectors.h); empty when no previous frame was posed (then toWorld stands for it).
  std::vector<Mat4> previousToWorld;
  /// The texture sampler over `textures` (textures/shading.cpp): made once, shared by every
  /// MaterialEvaluator of this scene. Nothing may change `textures` after it is made.
  SceneCacheSlot textureSampler;

  /// Adds the default material if none, checks indices; call after filling.
  void finalize();
  /// True when some primitive moves or deforms over the shutter: camera rays then draw a time.
  bool moving() const;
  /// World bounds of the finite primitives, moving ones over the whole shutter.
  Bounds3 bounds() const;
  /// Intersects primitive i (an analytic shape) with a world-space ray: hit.t, normal, uv.
  bool intersectShape(uint32_t i, const Ray& worldRay, Hit& hit) const;
  /// The one place that knows instance arrays: primitive i's object-to-world placement for
  /// instance `instance` (Hit::instance; 0 but for arrays), static. &toWorld, or for an array
  /// `scratch` filled with the instance's (InstanceArray::placement).
  const Transform& placement(uint32_t i, uint32_t instance, Transform& scratch) const {
    const Primitive& p = primitives[i];
    if (!p.instances) return p.toWorld;
    scratch = p.instances->placement(instance);
    return scratch;
  }
  /// Object id (objectid AOV, Cryptomatte) and name of instance `instance` of primitive i.
  int objectId(uint32_t i, uint32_t instance) const {
    const Primitive& p = primitives[i];
    return p.instances ? p.instances->firstObjectId + int(p.instances->index(instance))
                       : p.objectId;
  }
  std::string objectName(uint32_t i, uint32_t instance) const;
  /// The surface at a hit found by an accelerator.
  SurfacePoint surface(const Ray& ray, const Hit& hit) const;
  const Material& material(int i) const { return materials[size_t(i)]; }
};

}  // namespace tray
