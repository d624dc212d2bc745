#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

#include "lights/light_sampler.h"

namespace tray {

/// Lights chosen by their estimated contribution at the receiver, through a bounding volume
/// hierarchy of light bounds (Conty Estevez & Kulla 2018, "Importance Sampling of Many Lights
/// with Adaptive Tree Splitting"; the structure of pbrt-v4 12.6.3's BVHLightSampler, without
/// the splitting). Finite lights (emissive triangles and shapes, point and spot lights) are
/// the tree's leaves, one light each; descending, a child is taken in proportion to
/// LightBounds::importance at the receiver (near it, the sum of its own children's: weight()),
/// so a choice costs O(depth). Infinite lights (suns, environments) stand beside the tree's
/// root, each weighed by its own importance (a sun by its irradiance on the receiver's plane,
/// an environment by pi x its mean radiance), where pbrt gives them fixed shares: a sun behind
/// the receiver is then never chosen, and one in front gets the share its light deserves.
/// Lights whose bounds have no strength are never chosen. Built once, binned over 12 buckets
/// per axis by the paper's cost (power x orientation measure x surface area x the split axis'
/// aspect); queries allocate nothing.
class BvhLightSampler final : public LightSampler {
 public:
  explicit BvhLightSampler(const std::vector<LightBounds>& bounds);
  /// Inline, and LightSet calls it through the final class, without the virtual call: with no
  /// infinite light the tree takes all of u (callgrind, Cornell box: ~95 -> ~30 instructions
  /// per choice).
  int sample(const LightSampleContext& ctx, float u, float& pmf) const override {
    return sample(ctx, u, pmf, nullptr);
  }
  /// sample(), also giving in *soleInfinitePmf (when not null) pmf(ctx, i) for the scene's
  /// infinite light i when it has exactly one, bit for bit, and -1 otherwise: what an escape
  /// from the receiver's next segment weighs the environment by (PathEstimator::escape), for
  /// one top-level importance less per escape.
  int sample(const LightSampleContext& ctx, float u, float& pmf, float* soleInfinitePmf) const {
    // An environment alone: importance phi of a total phi, wherever the receiver is.
    if (soleAmbient_ >= 0) {
      if (soleInfinitePmf) *soleInfinitePmf = 1.0f;
      return pmf = 1.0f, soleAmbient_;
    }
    if (!infinite_.empty() || nodes_.empty()) return sampleTop(ctx, u, pmf, soleInfinitePmf);
    if (soleInfinitePmf) *soleInfinitePmf = -1.0f;
    // The tree alone: weight 1 of a total 1. u x 1, u / 1 and 1 / 1 are exact, so the choice
    // and the pmf are sampleTop's, bit for bit.
    u = std::min(u, kOneMinusEpsilon);
    u = std::max(u, 0.0f);
    pmf = 1.0f;
    return fixedTree_ ? descend<true>(ctx, u, pmf) : descendAny(ctx, u, pmf);
  }
  float pmf(const LightSampleContext& ctx, int light) const override {
    if (soleAmbient_ >= 0) return light == soleAmbient_ ? 1.0f : 0.0f;
    if (!infinite_.empty()) return pmfTop(ctx, light);
    if (light < 0 || size_t(light) >= trail_.size() || !inTree_[size_t(light)]) return 0.0f;
    const uint64_t trail = trail_[size_t(light)];  // the tree alone: p 1, as above
    return fixedTree_ ? pmfInTree<true>(ctx, trail, 1.0f) : pmfAny(ctx, trail, 1.0f);
  }
  /// The light whose pmf sample() gives in *soleInfinitePmf: the only infinite light that can
  /// be chosen, or -1 when there are none or several.
  int soleInfinite() const { return infinite_.size() == 1 ? infiniteLight_[0] : -1; }
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
  static constexpr float kOneMinusEpsilon = 0.99999994f;
  /// sample() and pmf() with infinite lights beside the tree (or no tree).
  int sampleTop(const LightSampleContext& ctx, float u, float& pmf, float* soleInfinitePmf) const;
  float pmfTop(const LightSampleContext& ctx, int light) const;
  /// From the root down to a leaf by u (in [0,1)), p times each branch's probability: the
  /// leaf's light. kFixed: every interior node has its fixedLeft (fixedTree_). Inline only
  /// then: inlined with the importance calls, the loop cost the integrator's step more than
  /// it saved (callgrind, EmissiveStrengthTest: +45 instructions per sample).
  template <bool kFixed>
  int descend(const LightSampleContext& ctx, float u, float& p) const {
    uint32_t n = 0;
    while (!nodes_[n].leaf) {
      const float pLeft = kFixed ? nodes_[n].fixedLeft : leftProbability(n, ctx);
      if (u < pLeft) {
        u = std::min(u / pLeft, kOneMinusEpsilon);
        p *= pLeft;
        n = n + 1;
      } else {
        u = std::min((u - pLeft) / (1.0f - pLeft), kOneMinusEpsilon);
        p *= 1.0f - pLeft;
        n = nodes_[n].index;
      }
    }
    return int(nodes_[n].index);
  }
  /// p times the probability of each branch along a light's trail.
  template <bool kFixed>
  float pmfInTree(const LightSampleContext& ctx, uint64_t trail, float p) const {
    uint32_t n = 0;
    for (int level = 0; !nodes_[n].leaf; ++level) {
      const float pLeft = kFixed ? nodes_[n].fixedLeft : leftProbability(n, ctx);
      if (trail & (uint64_t(1) << level)) {
        p *= 1.0f - pLeft;
        n = nodes_[n].index;
      } else {
        p *= pLeft;
        n = n + 1;
      }
    }
    return p;
  }
  /// descend<false> and pmfInTree<false>, out of line.
  int descendAny(const LightSampleContext& ctx, float u, float& p) const;
  float pmfAny(const LightSampleContext& ctx, uint64_t trail, float p) const;
  /// The tree's weight at the top level.
  float rootWeight(const LightSampleContext& ctx) const;
  /// The top level's total weight: the infinite lights' importances and the tree's (root).
  float topTotal(const LightSampleContext& ctx, float& root) const;
  /// The probability of taking an interior node's left child (1/2 when neither child can
  /// light the receiver).
  float leftProbability(uint32_t node, const LightSampleContext& ctx) const {
    const float fixed = nodes_[node].fixedLeft;
    return fixed >= 0 ? fixed : leftByImportance(node, ctx);
  }
  float leftByImportance(uint32_t node, const LightSampleContext& ctx) const;
  /// A child's weight at the receiver: its bounds' importance, or, when the receiver lies
  /// within twice the child's bounding radius of its centre, the sum of its own two
  /// children's importances (a leaf: its own). Near a cluster its one box says little (seen
  /// from inside or beside it, all of its strength at its centre, whatever its lights face);
  /// its halves' boxes are tighter. One level finer only, and only near: two importances more
  /// per level where it applies (issue 37: chooser efficiency on the many-light scenes 0.41
  /// -> 0.52-0.55, squared error x CPU time 1.4-1.6x lower; docs/bench/light-bvh-importance-
  /// 2026-12-07.md). Conservative as importance() is: 0 only where both halves are.
  float weight(uint32_t node, const LightSampleContext& ctx) const;

  std::vector<Node> nodes_;
  std::vector<LightBounds> infinite_;  ///< the infinite lights' bounds ...
  std::vector<int> infiniteLight_;     ///< ... and their light indices
  std::vector<int> infiniteSlot_;      ///< per light: its place in infinite_, or -1
  std::vector<uint64_t> trail_;        ///< per light: bit k set = right turn at depth k
  std::vector<bool> inTree_;           ///< per light
  int depth_ = 0;
  /// The light when the only one that can be chosen is an environment (kAmbient), else -1.
  int soleAmbient_ = -1;
  bool fixedTree_ = false;  ///< every interior node has fixedLeft (e.g. one quad's 2 triangles)
};

}  // namespace tray
