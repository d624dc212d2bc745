#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "core/bounds.h"
#include "core/math.h"

namespace tray {

/// Indexed triangle mesh in object space, one material (one glTF primitive). Instanced by
/// Primitives that reference it by index, so it is stored and built once.
struct TriangleMesh {
  std::string name;
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;        ///< per vertex; empty = flat shading
  std::vector<Vec2> uvs;            ///< per vertex (TEXCOORD_0); may be empty
  std::vector<Vec2> uvs1;           ///< per vertex (TEXCOORD_1); may be empty
  std::vector<Vec3> tangents;       ///< per vertex, xyz (glTF TANGENT or computeTangents())
  std::vector<float> tangentSigns;  ///< per vertex: bitangent = sign * cross(normal, tangent)
  std::vector<Color> colors;        ///< per vertex (COLOR_0, linear RGB); may be empty
  std::vector<float> colorAlphas;   ///< per vertex (COLOR_0's alpha); empty = 1
  std::vector<uint32_t> indices;    ///< 3 per triangle
  /// Motion blur of a deforming mesh (skins, morphs; core/motion.h): every vertex's position at
  /// motion steps evenly spaced over the shutter, linearly interpolated in between as Embree's
  /// vertex motion. Empty: the mesh does not deform over the shutter (`positions` holds).
  std::vector<std::vector<Vec3>> positionSteps;
  int material = 0;
  size_t triangleCount() const { return indices.size() / 3; }
  /// Bounds of the vertices, over the whole shutter for a deforming mesh.
  Bounds3 bounds() const {
    Bounds3 b;
    for (const auto& p : positions) b.extend(p);
    for (const auto& step : positionSteps)
      for (const auto& p : step) b.extend(p);
    return b;
  }
};

}  // namespace tray
