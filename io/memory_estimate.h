#pragma once
// tray-render --max-memory: what a scene will allocate, estimated from what the file states
// before the big allocations happen, and the one-line refusal when it is more than allowed.
#include <cstdint>
#include <string>

namespace tray {

/// Bytes a scene needs, by kind; each filled as soon as it is known (buffers from the JSON
/// before any is read, textures from the image headers before decoding, geometry from the
/// triangle count before the accelerator is built).
struct MemoryEstimate {
  uint64_t buffers = 0;      ///< sum of the distinct buffers' byteLength
  uint64_t textures = 0;     ///< width x height x channels x bytes per code, per decoded image
  uint64_t geometry = 0;     ///< triangles and placements (kGeometryBytesPerTriangle, ...)
  uint64_t environment = 0;  ///< an environment map's decoded floats (width x height x 12)
  uint64_t total() const { return buffers + textures + geometry + environment; }
};

/// Mesh arrays plus the accelerator, per triangle, an estimate: an indexed mesh holds 12 bytes
/// of indices and 0.5 to 1 vertex of 48 bytes (position, normal, uv, tangent) per triangle;
/// Embree's BVH with its triangle leaves about as much again.
constexpr uint64_t kGeometryBytesPerTriangle = 160;
/// Per placed primitive (a node's mesh primitive, an EXT_mesh_gpu_instancing instance): its
/// Primitive (216 bytes), its Embree instance geometry (~400) and the integrators' tables; 10^6
/// instances measured 683 bytes each with Embree (docs/bench/instancing-2026-12-06.md).
constexpr uint64_t kBytesPerPlacement = 700;
/// Per instance of an instance array (core/instance_array.h): its 48-byte matrix and its share
/// of the accelerator's top tree (docs/bench/instancing-arrays-2026-12-06.md).
constexpr uint64_t kBytesPerArrayInstance = 160;

/// Throws tray::Error (input) "SCENE: needs about N MB (buffers a MB, textures b MB, geometry
/// c MB[, environment d MB]), more than --max-memory M MB" when e.total() > limitBytes;
/// limitBytes 0: no limit.
void checkMemory(const std::string& scene, const MemoryEstimate& e, uint64_t limitBytes);

}  // namespace tray
