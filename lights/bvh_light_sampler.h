#pragma once
#include <cstdint>
#include <vector>

#include "lights/light_sampler.h"

namespace tray {

/// Lights chosen by their estimated contribution at the receiver, through a bounding volume
/// hierarchy of light bounds (Conty Estevez & Kulla 2018, "Importance Sampling of Many Lights
/// with Adaptive Tree Splitting"; the structure of pbrt-v4 12.6.3's BVHLightSampler, without
/// the splitting). Finite lights (emissive triangles and shapes, point and spot lights) are
/// the tree's leaves, one light each; descending, a child is taken in proportion to
/// LightBounds::importance at the receiver, so a choice costs O(depth). Infinite lights (suns,
/// environments) stand beside the tree's root, each weighed by its own importance (a sun by
/// its irradiance on the receiver's plane, an environment by pi x its mean radiance), where
/// pbrt gives them fixed shares: a sun behind the receiver is then never chosen, and one in
/// front gets the share its light deserves. Lights whose bounds have no strength are never
/// chosen. Built once, binned over 12 buckets per axis by the paper's cost (power x
/// orientation measure x surface area x the split axis' aspect); queries allocate nothing.
class BvhLightSampler final : public LightSampler {
 public:
  explicit BvhLightSampler(const std::vector<LightBounds>& bounds);
  int sample(const LightSampleContext& ctx, float u, float& pmf) const override;
  float pmf(const LightSampleContext& ctx, int light) const override;
  size_t nodeCount() const { return nodes_.size(); }
  /// Levels below the root of the deepest leaf (0: one light or none).
  int depth() const { return depth_; }

 private:
  struct Node {
    LightBounds bounds;
    uint32_t index = 0;  ///< interior: the right child (the left one follows); leaf: the light
    bool leaf = false;
    /// Interior nodes whose children differ only in strength (a quad's two triangles): the
    /// left child's probability, the same at every receiver; -1 otherwise.
    float fixedLeft = -1;
  };
  struct Item {
    LightBounds bounds;
    Vec3 centroid;
    uint32_t light;
  };
  uint32_t build(std::vector<Item>& items, size_t begin, size_t end, int depth, uint64_t trail);
  size_t split(std::vector<Item>& items, size_t begin, size_t end, bool balanced) const;
  /// The tree's weight at the top level.
  float rootWeight(const LightSampleContext& ctx) const;
  /// The top level's total weight: the infinite lights' importances and the tree's (root).
  float topTotal(const LightSampleContext& ctx, float& root) const;
  /// The probability of taking an interior node's left child (1/2 when neither child can
  /// light the receiver).
  float leftProbability(uint32_t node, const LightSampleContext& ctx) const;

  std::vector<Node> nodes_;
  std::vector<LightBounds> infinite_;  ///< the infinite lights' bounds ...
  std::vector<int> infiniteLight_;     ///< ... and their light indices
  std::vector<int> infiniteSlot_;      ///< per light: its place in infinite_, or -1
  std::vector<uint64_t> trail_;        ///< per light: bit k set = right turn at depth k
  std::vector<bool> inTree_;           ///< per light
  int depth_ = 0;
};

}  // namespace tray
