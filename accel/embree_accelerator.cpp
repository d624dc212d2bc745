#include "accel/embree_accelerator.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <cstring>
#include <mutex>
#include <new>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

#include "accel/embree_alpha_filter.h"
#include "accel/embree_batch.h"
#include "accel/embree_instance_array.h"
#include "accel/embree_native.h"
#include "accel/embree_rays.h"
#include "accel/embree_shape_geometry.h"
#include "core/error.h"
#include "core/scene.h"

namespace tray {
namespace {

/// Intersect context for all-hits queries: the filter records every hit and rejects it, so
/// traversal continues (Embree's tutorials/next_hit).
struct AllHitsContext {
  RTCIntersectContext base;
  const Scene* scene;
  std::vector<Hit>* hits;
  const std::vector<RTCGeometry>* subdivisions;  ///< per primitive; see refineNativeHit
};

/// A subdivision surface's hit gets its limit normal (accel/embree_native.h); others unchanged.
void refineNativeHit(const std::vector<RTCGeometry>& subdivisions, Hit& hit) {
  if (hit.primitive < subdivisions.size() && subdivisions[hit.primitive])
    embreeSubdivisionNormal(subdivisions[hit.primitive], hit);
}

void allHitsFilter(const RTCFilterFunctionNArguments* args) {
  auto* ctx = reinterpret_cast<const AllHitsContext*>(args->context);
  const RTCHit* h = reinterpret_cast<const RTCHit*>(args->hit);
  const RTCRay* r = reinterpret_cast<const RTCRay*>(args->ray);
  Hit hit = hitFromEmbree(*h, r->tfar, *ctx->scene);
  // Inside an instance array the filter sees the mesh's geometry id 0, not the instance.
  if (ctx->scene->primitives[hit.primitive].instances) hit.instance = embreeArrayInstanceInFlight();
  refineNativeHit(*ctx->subdivisions, hit);
  // Embree may report a triangle more than once (RenderKit/embree#12): keep one.
  auto same = [&](const Hit& o) {
    return o.primitive == hit.primitive && o.instance == hit.instance &&
           o.triangle == hit.triangle && o.t == hit.t && o.material == hit.material;
  };
  if (std::none_of(ctx->hits->begin(), ctx->hits->end(), same)) ctx->hits->push_back(hit);
  args->valid[0] = 0;  // reject: keep traversing
}

class EmbreeAccelerator final : public Accelerator {
 public:
  EmbreeAccelerator(const Scene& scene, EmbreeBatch batch) : scene_(scene), batch_(batch) {
    device_ = rtcNewDevice(nullptr);
    if (!device_) throw Error("Embree: cannot create a device", Error::Kind::kRender);
    rtcSetDeviceErrorFunction(device_, onError, this);
    rtcSetDeviceMemoryMonitorFunction(device_, onMemory, this);
    build();
  }
  ~EmbreeAccelerator() override {
    if (top_) rtcReleaseScene(top_);
    for (auto& [mesh, s] : meshScenes_) rtcReleaseScene(s);
    for (RTCScene s : nativeScenes_) rtcReleaseScene(s);
    for (RTCGeometry g : subdivisions_)
      if (g) rtcReleaseGeometry(g);
    rtcReleaseDevice(device_);
  }

  bool intersect(const Ray& ray, Hit& hit) const override {
    AlphaRayContext ctx(scene_, ray);  // alpha-tested meshes' filters read it
    RTCRayHit rh = toEmbree(ray);
    rtcIntersect1(top_, &ctx.base, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
    hit = hitFromEmbree(rh.hit, rh.ray.tfar, scene_);
    if (!subdivisions_.empty()) refineNativeHit(subdivisions_, hit);
    return true;
  }

  bool occluded(const Ray& ray) const override {
    AlphaRayContext ctx(scene_, ray);
    RTCRay r;
    toEmbreeShadow(ray, r);
    rtcOccluded1(top_, &ctx.base, &r);
    return r.tfar < 0;
  }

  // Batches through the stream or packet API (accel/embree_batch.cpp). User geometry's
  // callbacks read one ray (N = 1), so scenes with analytic shapes, and EmbreeBatch::kLoop,
  // trace ray by ray.
  void intersectBatch(std::span<const Ray> rays, std::span<Hit> hits,
                      std::span<uint8_t> found) const override {
    if (!streamable()) return Accelerator::intersectBatch(rays, hits, found);
    embreeIntersectBatch(top_, scene_, batch_, rays, hits, found);
  }
  void intersectCoherentBatch(std::span<const Ray> rays, std::span<Hit> hits,
                              std::span<uint8_t> found) const override {
    if (!streamable()) return Accelerator::intersectBatch(rays, hits, found);
    embreeIntersectBatch(top_, scene_, batch_, rays, hits, found, true);
  }
  void occludedBatch(std::span<const Ray> rays, std::span<uint8_t> blocked) const override {
    if (!streamable()) return Accelerator::occludedBatch(rays, blocked);
    embreeOccludedBatch(top_, scene_, batch_, rays, blocked);
  }

  void allHits(const Ray& ray, std::vector<Hit>& hits) const override {
    hits.clear();
    AllHitsContext ctx;
    rtcInitIntersectContext(&ctx.base);
    ctx.base.filter = allHitsFilter;
    ctx.scene = &scene_;
    ctx.hits = &hits;
    ctx.subdivisions = &subdivisions_;
    RTCRayHit rh = toEmbree(ray);
    rtcIntersect1(top_, &ctx.base, &rh);
    std::sort(hits.begin(), hits.end(), [](const Hit& a, const Hit& b) {
      if (a.t != b.t) return a.t < b.t;
      if (a.primitive != b.primitive) return a.primitive < b.primitive;
      return a.triangle < b.triangle;
    });
  }

  size_t memoryBytes() const override { return size_t(std::max<int64_t>(memory_.load(), 0)); }

 private:
  static void onError(void* self, RTCError code, const char* message) {
    auto* a = static_cast<EmbreeAccelerator*>(self);
    std::lock_guard<std::mutex> lock(a->errorMutex_);
    if (a->error_.empty()) {
      a->error_ = message ? message : "unknown error";
      a->outOfMemory_ = code == RTC_ERROR_OUT_OF_MEMORY;
    }
  }
  static bool onMemory(void* self, ssize_t bytes, bool) {
    static_cast<EmbreeAccelerator*>(self)->memory_ += bytes;
    return true;
  }
  void checkError() {
    std::lock_guard<std::mutex> lock(errorMutex_);
    if (outOfMemory_) throw std::bad_alloc();  // main names the phase, as for any allocation
    if (!error_.empty()) throw Error("Embree: " + error_, Error::Kind::kRender);
  }

  // Scenes with Embree's own curves or subdivision surfaces also trace ray by ray: their hits
  // go through intersect() (refineNativeHit).
  bool streamable() const { return batch_ != EmbreeBatch::kLoop && !hasUserGeometry_; }

  /// A new Embree-owned buffer of `count` items of `stride` bytes, filled from `data` (`slot`:
  /// the time step of a vertex buffer).
  void copyToEmbree(RTCGeometry g, RTCBufferType type, RTCFormat format, const void* data,
                    size_t stride, size_t count, unsigned slot = 0) {
    void* dst = rtcSetNewGeometryBuffer(g, type, slot, format, stride, count);
    if (!dst) {
      checkError();
      throw Error("Embree: cannot allocate a geometry buffer", Error::Kind::kRender);
    }
    std::memcpy(dst, data, stride * count);
  }

  RTCScene meshScene(uint32_t meshIndex) {
    auto it = meshScenes_.find(meshIndex);
    if (it != meshScenes_.end()) return it->second;
    const TriangleMesh& m = scene_.meshes[meshIndex];
    RTCScene s = rtcNewScene(device_);
    // ROBUST: watertight traversal, no cracks on shared edges (RenderKit/embree#381).
    rtcSetSceneFlags(s, RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
    rtcSetSceneBuildQuality(s, RTC_BUILD_QUALITY_HIGH);
    // A deforming mesh: one vertex buffer per time step, interpolated by Embree.
    RTCGeometry g = m.positionSteps.empty() ? triangleGeometry(m, {&m.positions, 1})
                                            : triangleGeometry(m, m.positionSteps);
    rtcCommitGeometry(g);
    rtcAttachGeometryByID(s, g, 0);
    rtcReleaseGeometry(g);
    rtcCommitScene(s);
    meshScenes_[meshIndex] = s;
    return s;
  }

  /// Triangle geometry of mesh m: its triangles over the vertex buffers `steps` (one per time
  /// step, which Embree interpolates by the ray's time; one for a static mesh), with its alpha
  /// filter.
  RTCGeometry triangleGeometry(const TriangleMesh& m, std::span<const std::vector<Vec3>> steps) {
    RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    // Copied into buffers Embree allocates, not shared: Embree reads the last vertex with a
    // 16-byte SSE load, so a shared float3 array needs padding after it (docs of
    // rtcSetSharedGeometryBuffer); the mesh's std::vector has none, and valgrind saw reads past
    // its end. Embree pads the buffers it allocates itself (rtcSetNewGeometryBuffer docs).
    if (steps.size() > 1) rtcSetGeometryTimeStepCount(g, unsigned(steps.size()));
    for (unsigned k = 0; k < steps.size(); ++k)
      copyToEmbree(g, RTC_BUFFER_TYPE_VERTEX, RTC_FORMAT_FLOAT3, steps[k].data(), sizeof(Vec3),
                   steps[k].size(), k);
    copyToEmbree(g, RTC_BUFFER_TYPE_INDEX, RTC_FORMAT_UINT3, m.indices.data(), 3 * sizeof(uint32_t),
                 m.triangleCount());
    attachAlphaFilter(g, scene_, m);
    return g;
  }

  /// Mesh primitive p's triangles in world space (its toWorld applied to each vertex), as
  /// triangle geometry of the top scene; hits then carry its primitive index as geometry id.
  RTCGeometry worldMeshGeometry(const Primitive& p) {
    const TriangleMesh& m = scene_.meshes[p.mesh];
    std::vector<Vec3> world(m.positions.size());
    for (size_t k = 0; k < world.size(); ++k) world[k] = p.toWorld.point(m.positions[k]);
    return triangleGeometry(m, {&world, 1});
  }

  /// An instance's placement: its one transform, or for a moving primitive one per motion step,
  /// which Embree interpolates linearly by the ray's time (core/motion.h does the same).
  static void setInstanceMotion(RTCGeometry g, const Primitive& p) {
    if (p.motion.empty()) {
      rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT3X4_ROW_MAJOR, &p.toWorld.m.m[0][0]);
      return;
    }
    rtcSetGeometryTimeStepCount(g, unsigned(p.motion.size()));
    for (unsigned k = 0; k < p.motion.size(); ++k)
      rtcSetGeometryTransform(g, k, RTC_FORMAT_FLOAT3X4_ROW_MAJOR, &p.motion[k].m[0][0]);
  }

  /// Embree's own curves or subdivision surface of primitive i (accel/embree_native.h), in a
  /// scene of its own placed by an instance, as a mesh is: hits then arrive in object space.
  RTCGeometry nativeInstance(uint32_t i, RTCGeometry native) {
    const Primitive& p = scene_.primitives[i];
    hasUserGeometry_ = true;  // trace ray by ray (streamable)
    rtcCommitGeometry(native);
    RTCScene s = rtcNewScene(device_);
    rtcSetSceneFlags(s, RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
    rtcSetSceneBuildQuality(s, RTC_BUILD_QUALITY_HIGH);
    rtcAttachGeometryByID(s, native, 0);
    if (embreeNativeIsSubdivision(*p.shape)) {
      subdivisions_.resize(scene_.primitives.size(), nullptr);
      subdivisions_[i] = native;  // kept for rtcInterpolate
    } else {
      rtcReleaseGeometry(native);
    }
    rtcCommitScene(s);
    checkError();
    nativeScenes_.push_back(s);
    RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(g, s);
    setInstanceMotion(g, p);
    return g;
  }

  /// Instance array i as one user geometry over its instances (accel/embree_instance_array.h).
  RTCGeometry instanceArray(uint32_t i) {
    const Primitive& p = scene_.primitives[i];
    // Traced ray by ray: 8-wide packets reach the callbacks, which take them lane by lane, and
    // cost 1.38x the render time at 10^6 instances (0.764 against 1.056 CPU s, bench/
    // instancing_bench, docs/bench/instancing-arrays-2026-12-06.md).
    hasUserGeometry_ = true;
    arrays_[i] = {p.instances.get(), meshScene(p.mesh), scene_.meshes[p.mesh].bounds(), {}};
    return embreeInstanceArray(device_, arrays_[i]);
  }

  void build() {
    top_ = rtcNewScene(device_);
    rtcSetSceneFlags(top_, RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
    userData_.resize(scene_.primitives.size());
    for (const Primitive& p : scene_.primitives)
      if (p.instances) arrays_.resize(scene_.primitives.size());
    // Instance arrays: no RTC_SCENE_FLAG_COMPACT. Over single instances it saved 21 MiB at
    // 10^6 at the same speed; over groups of kEmbreeArrayGroup it saves 1.5 MiB and costs 5% of
    // the render time (docs/bench/instancing-arrays-time-2026-12-07.md).
    const std::vector<uint8_t> flat = embreeFlattenedMeshes(scene_);
    // Two levels (rtcSetSceneBuildQuality(3): the low quality builds a tree per geometry and
    // one over them) for small meshes, one tree when a big one is flattened
    // (kEmbreeOneTreeTriangles).
    rtcSetSceneBuildQuality(
        top_, embreeTwoLevelTop(scene_, flat) ? RTC_BUILD_QUALITY_LOW : RTC_BUILD_QUALITY_MEDIUM);
    // Instance arrays: the medium (SAH) quality over their groups of kEmbreeArrayGroup
    // instances. Over single instances it held 71 MiB at 10^6 and peaked 32 above that, over
    // the memory budget, and the low (Morton) quality was kept, for 1.22x the render time
    // (docs/bench/instancing-arrays-2026-12-06.md); over groups of 8 it holds an eighth and
    // renders in 0.84x the low one's time over single instances
    // (docs/bench/instancing-arrays-time-2026-12-07.md).
    if (!arrays_.empty()) rtcSetSceneBuildQuality(top_, RTC_BUILD_QUALITY_MEDIUM);
    for (uint32_t i = 0; i < scene_.primitives.size(); ++i) {
      const Primitive& p = scene_.primitives[i];
      RTCGeometry g;
      if (flat[i]) {
        g = worldMeshGeometry(p);
      } else if (p.instances) {
        if (scene_.meshes[p.mesh].triangleCount() == 0) continue;
        g = instanceArray(i);
      } else if (p.kind == Primitive::Kind::kMesh) {
        if (scene_.meshes[p.mesh].triangleCount() == 0) continue;
        g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_INSTANCE);
        rtcSetGeometryInstancedScene(g, meshScene(p.mesh));
        setInstanceMotion(g, p);
      } else if (RTCGeometry native = embreeNativeGeometry(device_, *p.shape)) {
        g = nativeInstance(i, native);
      } else {
        hasUserGeometry_ = true;
        userData_[i] = {&scene_, i};
        g = embreeShapeGeometry(device_, userData_[i]);
      }
      rtcCommitGeometry(g);
      rtcAttachGeometryByID(top_, g, i);
      rtcReleaseGeometry(g);
    }
    rtcCommitScene(top_);
    checkError();
  }

  const Scene& scene_;
  EmbreeBatch batch_;
  bool hasUserGeometry_ = false;
  RTCDevice device_ = nullptr;
  RTCScene top_ = nullptr;
  std::unordered_map<uint32_t, RTCScene> meshScenes_;
  std::vector<RTCScene> nativeScenes_;     ///< one per curves / subdivision primitive
  std::vector<RTCGeometry> subdivisions_;  ///< per primitive: its subdivision geometry or null
  std::vector<ShapeUserData> userData_;
  std::vector<EmbreeArrayData> arrays_;  ///< per primitive when the scene has instance arrays
  std::atomic<int64_t> memory_{0};
  std::mutex errorMutex_;
  std::string error_;
  bool outOfMemory_ = false;
};

}  // namespace

std::vector<uint8_t> embreeFlattenedMeshes(const Scene& scene) {
  std::vector<int> uses(scene.meshes.size(), 0);
  for (const Primitive& p : scene.primitives)
    if (p.kind == Primitive::Kind::kMesh) ++uses[p.mesh];
  std::vector<uint8_t> flat(scene.primitives.size(), 0);
  for (size_t i = 0; i < flat.size(); ++i) {
    const Primitive& p = scene.primitives[i];
    if (p.kind != Primitive::Kind::kMesh) continue;
    const TriangleMesh& m = scene.meshes[p.mesh];
    flat[i] = uses[p.mesh] == 1 && p.motion.empty() && !p.instances && m.positionSteps.empty() &&
              m.triangleCount() > 0;
  }
  return flat;
}

bool embreeTwoLevelTop(const Scene& scene, const std::vector<uint8_t>& flattened) {
  size_t placements = 0;  // an instance array counts its instances
  for (const Primitive& p : scene.primitives) placements += p.instanceCount();
  if (placements >= kEmbreeTwoLevelMaxPrimitives) return false;
  for (size_t i = 0; i < flattened.size(); ++i)
    if (flattened[i] &&
        scene.meshes[scene.primitives[i].mesh].triangleCount() >= kEmbreeOneTreeTriangles)
      return false;
  return true;
}

std::unique_ptr<Accelerator> makeEmbreeAccelerator(const Scene& scene) {
  return makeEmbreeAccelerator(scene, EmbreeBatch::kPacket8);
}

std::unique_ptr<Accelerator> makeEmbreeAccelerator(const Scene& scene, EmbreeBatch batch) {
  return std::make_unique<EmbreeAccelerator>(scene, batch);
}

}  // namespace tray
