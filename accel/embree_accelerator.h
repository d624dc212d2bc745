#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "core/accelerator.h"

namespace tray {

/// How Accelerator::intersectBatch/occludedBatch reach Embree (bench/path_bench measures them).
/// (The stream API's coherent flag is not offered: with Embree 3.13.5 it did not return on
/// the Cornell box, even for 256 rays; docs/wavefront.md.)
enum class EmbreeBatch {
  kLoop,     ///< rtcIntersect1 per ray, as the default implementation
  kStream,   ///< rtcIntersect1M over the whole batch, flagged incoherent
  kPacket8,  ///< rtcIntersect8 over consecutive groups of 8 rays
};

/// Per primitive: whether Embree places it in the top scene as world-space triangles rather
/// than as an instance (as Mitsuba 3 places every mesh): a static mesh (no motion, no
/// deformation) used by this primitive alone. No per-instance ray transform; a mesh placed
/// several times stays one copy, instanced.
std::vector<uint8_t> embreeFlattenedMeshes(const Scene& scene);

/// When no flattened mesh has this many triangles, the top scene is built in two levels (a
/// tree per geometry and one over them, Embree 3's RTC_BUILD_QUALITY_LOW); when one has, as one
/// tree over every triangle (the default quality). Measured (docs/accelerators.md), per sample
/// against instances of every mesh under 1024 triangles: the Cornell box (8 meshes, 36
/// triangles) 1.13x in two levels, 0.94x in one tree; with 100 more small meshes (1236
/// triangles) 1.42x and 1.16x; the heavy spheres (98 meshes of ~10k triangles) 0.93x in two
/// levels, 1.06x in one tree; the heavy helmets 1.14-1.16x either way.
constexpr size_t kEmbreeOneTreeTriangles = 1024;
/// Nor from this many placed primitives (EXT_mesh_gpu_instancing, docs/instancing.md): the two
/// levels then make a tree per instance. bench/instancing_bench at 10^5 and 10^6 instances: one
/// tree builds in 0.5-0.7x the CPU time with 14 and 92 MiB less peak memory, renders as fast;
/// at 10^4 the two are alike.
constexpr size_t kEmbreeTwoLevelMaxPrimitives = 10'000;
/// Whether the top scene of `scene` is built in two levels, given embreeFlattenedMeshes.
bool embreeTwoLevelTop(const Scene& scene, const std::vector<uint8_t>& flattened);

/// Embree 3 traversal: meshes as triangle geometry built once per mesh and placed by instances;
/// analytic shapes as user geometry calling Scene::intersectShape.
/// Batches as 8-wide packets (EmbreeBatch::kPacket8: the fastest of the three in path_bench's
/// --embree-modes on the Cornell box and MetalRoughSpheresNoTextures, docs/wavefront.md).
std::unique_ptr<Accelerator> makeEmbreeAccelerator(const Scene& scene);
/// Batches use `batch` where the scene has no user geometry (benchmarks compare them).
std::unique_ptr<Accelerator> makeEmbreeAccelerator(const Scene& scene, EmbreeBatch batch);

}  // namespace tray
