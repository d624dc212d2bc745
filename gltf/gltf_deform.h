#pragma once
// Vertex deformation at load time, before the accelerators are built: morph targets (glTF 2.0
// §3.7.2.2) and linear blend skinning (§3.7.3), for one time of the animation.
#include <vector>

#include "core/transform.h"
#include "core/triangle_mesh.h"
#include "gltf/gltf_animation.h"
#include "gltf/gltf_context.h"

namespace tray {

class Deformer {
 public:
  /// `poses`: per node, what the animation sets (empty: nothing animated); `world`: every
  /// node's world matrix at the same time. Checks every skin and the morph weights of every
  /// node with a morphed mesh (throws ctx.fail).
  Deformer(const GltfContext& ctx, const std::vector<NodePose>& poses,
           const std::vector<Mat4>& world);

  /// True when node `node`'s mesh needs geometry of its own: it is skinned, or its morph
  /// weights are not all zero.
  bool deforms(int node) const;
  /// Skinned meshes are placed in world space by their joints alone (glTF 2.0 §3.7.3.3: "only
  /// the joint transforms are applied"), not by the node's transform.
  bool skinned(int node) const;
  /// Morphs, then skins, primitive `primitive` of node `node`'s mesh: `mesh` holds its vertices
  /// as read (positions, normals, tangents), before any triangle is dropped.
  void apply(int node, size_t primitive, TriangleMesh& mesh) const;
  /// Vertices whose skin weights did not sum to 1 and were rescaled (one warning).
  size_t renormalisedVertices() const { return renormalised_; }

 private:
  void morph(int node, size_t primitive, TriangleMesh& mesh) const;
  void skin(int node, size_t primitive, TriangleMesh& mesh) const;

  const GltfContext& ctx_;
  std::vector<std::vector<float>> weights_;  ///< per node: morph weights (empty: no targets)
  std::vector<std::vector<Mat4>> joints_;    ///< per skin: joint world x inverse bind matrix
  mutable size_t renormalised_ = 0;
  mutable size_t displacements_ = 0;  ///< morph target vertices read, against kMaxDisplacements
};

/// Every node's world matrix from its local one, parents first (the graph is a checked forest).
std::vector<Mat4> worldMatrices(const GltfContext& ctx, const std::vector<Mat4>& local);

}  // namespace tray
