#pragma once
#include <memory>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/hit.h"
#include "core/light_desc.h"
#include "core/material.h"
#include "core/transform.h"
#include "core/shape.h"
#include "core/triangle_mesh.h"

namespace tray {

/// One placed object: a mesh instance or an analytic shape, with its object-to-world transform.
struct Primitive {
  enum class Kind { kMesh, kShape };
  Kind kind = Kind::kMesh;
  uint32_t mesh = 0;                   ///< kMesh: index into Scene::meshes
  std::shared_ptr<const Shape> shape;  ///< kShape
  Transform toWorld;
  int material = 0;  ///< kShape: its material (meshes carry their own)
  int objectId = 0;  ///< glTF node index, for AOVs and mattes
  std::string name;
};

/// A decoded texture image: linear float RGB, row 0 at the top (glTF's uv origin), filled by
/// the texture loader (io/gltf_images) or by tests. Colour textures are linearised from sRGB
/// when decoded, so that filtering happens on linear values.
struct TextureImage {
  std::string name;  ///< for messages: the file's path, or "image N" for embedded images
  int width = 0, height = 0;
  std::vector<float> pixels;  ///< width * height * 3
  std::vector<float> alpha;   ///< width * height, linear; empty = opaque or not needed
  bool srgb = false;          ///< the file's values were sRGB-decoded
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
  Environment environment;

  /// Adds the default material if none, checks indices; call after filling.
  void finalize();
  /// World bounds of the finite primitives.
  Bounds3 bounds() const;
  /// Intersects primitive i (an analytic shape) with a world-space ray: hit.t, normal, uv.
  bool intersectShape(uint32_t i, const Ray& worldRay, Hit& hit) const;
  /// The surface at a hit found by an accelerator.
  SurfacePoint surface(const Ray& ray, const Hit& hit) const;
  const Material& material(int i) const { return materials[size_t(i)]; }
};

}  // namespace tray
