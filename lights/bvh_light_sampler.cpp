#include "lights/bvh_light_sampler.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/error.h"

namespace tray {

namespace {

constexpr int kBuckets = 12;

/// The orientation measure M_Omega of a cone of normals theta_o emitting within theta_e
/// (Conty Estevez & Kulla eq. 1): the cosine-weighted solid angle it can light.
float orientationMeasure(const LightBounds& b) {
  const float thetaO = std::acos(std::clamp(b.cosTheta_o, -1.0f, 1.0f));
  const float thetaE = std::acos(std::clamp(b.cosTheta_e, -1.0f, 1.0f));
  const float thetaW = std::min(thetaO + thetaE, kPi);
  const float sinO = std::sin(thetaO);
  return 2.0f * kPi * (1.0f - b.cosTheta_o) +
         0.5f * kPi *
             (2.0f * thetaW * sinO - std::cos(thetaO - 2.0f * thetaW) - 2.0f * thetaO * sinO +
              b.cosTheta_o);
}

/// The cost of a node holding b (the paper's eq. 2 without the constant): strength x
/// orientation x size. Points have no surface area; the squared diagonal keeps sets of
/// point lights apart.
float cost(const LightBounds& b) {
  if (!(b.phi > 0)) return 0.0f;
  const Vec3 d = b.box.diagonal();
  return b.phi * orientationMeasure(b) * (b.box.surfaceArea() + lengthSquared(d));
}

float axisOf(const Vec3& v, int axis) { return axis == 0 ? v.x : axis == 1 ? v.y : v.z; }

/// Whether two bounds differ at most in strength, so that their importances are in the ratio
/// of their strengths wherever the receiver is.
bool sameShape(const LightBounds& a, const LightBounds& b) {
  auto same = [](const Vec3& x, const Vec3& y) { return x.x == y.x && x.y == y.y && x.z == y.z; };
  return same(a.box.lo, b.box.lo) && same(a.box.hi, b.box.hi) && same(a.w, b.w) &&
         a.cosTheta_o == b.cosTheta_o && a.cosTheta_e == b.cosTheta_e && a.twoSided == b.twoSided;
}

int ceilLog2(size_t n) {
  int k = 0;
  while ((size_t(1) << k) < n) ++k;
  return k;
}

}  // namespace

BvhLightSampler::BvhLightSampler(const std::vector<LightBounds>& bounds) {
  infiniteSlot_.assign(bounds.size(), -1);
  trail_.assign(bounds.size(), 0);
  inTree_.assign(bounds.size(), false);
  std::vector<Item> items;
  for (size_t i = 0; i < bounds.size(); ++i) {
    const LightBounds& b = bounds[i];
    if (!(b.phi > 0) || !std::isfinite(b.phi)) continue;  // never chosen
    if (b.kind != LightBounds::Kind::kFinite) {
      infiniteSlot_[i] = int(infinite_.size());
      infinite_.push_back(b);
      infiniteLight_.push_back(int(i));
    } else if (b.box.finite() && !b.box.empty()) {
      items.push_back({b, b.box.center(), uint32_t(i)});
    }
  }
  if (items.size() > (size_t(1) << 40)) throw Error("too many lights for the light BVH");
  if (!items.empty()) build(items, 0, items.size(), 0, 0);
  fixedTree_ = std::all_of(nodes_.begin(), nodes_.end(),
                           [](const Node& n) { return n.leaf || n.fixedLeft >= 0; });
  // sampleTop would give it pmf phi / phi = 1 (phi is finite and positive here), any u.
  if (items.empty() && infinite_.size() == 1 && infinite_[0].kind == LightBounds::Kind::kAmbient)
    soleAmbient_ = infiniteLight_[0];
}

uint32_t BvhLightSampler::build(std::vector<Item>& items, size_t begin, size_t end, int depth,
                                uint64_t trail) {
  const uint32_t index = uint32_t(nodes_.size());
  nodes_.emplace_back();
  depth_ = std::max(depth_, depth);
  if (end - begin == 1) {
    nodes_[index] = {items[begin].bounds, items[begin].light, true};
    trail_[items[begin].light] = trail;
    inTree_[items[begin].light] = true;
    return index;
  }
  // The trail has 64 bits: near that depth, halve by count so that the rest stays shallow.
  const bool balanced = depth + ceilLog2(end - begin) >= 60;
  const size_t mid = split(items, begin, end, balanced);
  const uint32_t left = build(items, begin, mid, depth + 1, trail);
  const uint32_t right = build(items, mid, end, depth + 1, trail | (uint64_t(1) << depth));
  const LightBounds &l = nodes_[left].bounds, &r = nodes_[right].bounds;
  if (sameShape(l, r)) nodes_[index].fixedLeft = l.phi / (l.phi + r.phi);
  nodes_[index].bounds = unite(l, r);
  nodes_[index].index = right;
  return index;
}

size_t BvhLightSampler::split(std::vector<Item>& items, size_t begin, size_t end,
                              bool balanced) const {
  Bounds3 centroids, box;
  for (size_t i = begin; i < end; ++i) {
    centroids.extend(items[i].centroid);
    box.extend(items[i].bounds.box);
  }
  const Vec3 extent = centroids.diagonal(), size = box.diagonal();
  const float largest = maxComponent(size);
  float bestCost = kInfinity;
  int bestAxis = -1, bestBucket = 0;
  for (int axis = 0; axis < 3 && !balanced; ++axis) {
    const float lo = axisOf(centroids.lo, axis), width = axisOf(extent, axis);
    if (!(width > 0)) continue;
    auto bucketOf = [&](const Item& it) {
      return std::min(kBuckets - 1, int(kBuckets * (axisOf(it.centroid, axis) - lo) / width));
    };
    std::array<LightBounds, kBuckets> buckets{};
    for (size_t i = begin; i < end; ++i) {
      LightBounds& b = buckets[size_t(bucketOf(items[i]))];
      b = unite(b, items[i].bounds);
    }
    // Long thin boxes split across their length (the paper's K_r).
    const float aspect = largest / std::max(axisOf(size, axis), 1e-30f);
    std::array<float, kBuckets> below{};
    LightBounds acc;
    for (int k = 0; k < kBuckets - 1; ++k) {
      acc = unite(acc, buckets[size_t(k)]);
      below[size_t(k)] = cost(acc);
    }
    acc = LightBounds();
    for (int k = kBuckets - 1; k > 0; --k) {
      acc = unite(acc, buckets[size_t(k)]);
      const float c = aspect * (below[size_t(k - 1)] + cost(acc));
      if (c < bestCost) bestCost = c, bestAxis = axis, bestBucket = k;
    }
  }
  if (bestAxis >= 0) {
    const int axis = bestAxis;
    const float lo = axisOf(centroids.lo, axis), width = axisOf(extent, axis);
    auto mid = std::partition(
        items.begin() + long(begin), items.begin() + long(end), [&](const Item& it) {
          return std::min(kBuckets - 1, int(kBuckets * (axisOf(it.centroid, axis) - lo) / width)) <
                 bestBucket;
        });
    const size_t m = size_t(mid - items.begin());
    if (m > begin && m < end) return m;
  }
  // Balanced, or no split separates anything (equal centroids): halve by count along the
  // widest axis of the centroids.
  const int axis =
      extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
  const size_t m = begin + (end - begin) / 2;
  std::nth_element(items.begin() + long(begin), items.begin() + long(m), items.begin() + long(end),
                   [&](const Item& a, const Item& b) {
                     return axisOf(a.centroid, axis) < axisOf(b.centroid, axis);
                   });
  return m;
}

float BvhLightSampler::rootWeight(const LightSampleContext& ctx) const {
  if (nodes_.empty()) return 0.0f;
  // Alone at the top, the tree is taken whatever its weight (where it is 0, its leaves are
  // too, and the sample is lost either way): one importance fewer per choice.
  return infinite_.empty() ? 1.0f : nodes_[0].bounds.importance(ctx);
}

float BvhLightSampler::topTotal(const LightSampleContext& ctx, float& root) const {
  float total = 0;
  for (const LightBounds& b : infinite_) total += b.importance(ctx);
  root = rootWeight(ctx);
  return total + root;
}

float BvhLightSampler::weight(uint32_t n, const LightSampleContext& ctx) const {
  const Node& node = nodes_[n];
  if (!node.leaf) {
    // Within twice the bounding radius r of the centre: d^2 < 4 r^2, the diagonal squared.
    const Bounds3& box = node.bounds.box;
    if (lengthSquared(ctx.p - box.center()) < lengthSquared(box.diagonal()))
      return nodes_[n + 1].bounds.importance(ctx) + nodes_[node.index].bounds.importance(ctx);
  }
  return node.bounds.importance(ctx);
}

float BvhLightSampler::leftByImportance(uint32_t node, const LightSampleContext& ctx) const {
  const float left = weight(node + 1, ctx);
  const float right = weight(nodes_[node].index, ctx);
  const float sum = left + right;
  // Neither child can light the receiver though their parent's looser bounds said it might:
  // either way the sample is lost, but halves keep the pmfs a distribution.
  return sum > 0 && std::isfinite(sum) ? left / sum : 0.5f;
}

int BvhLightSampler::sampleTop(const LightSampleContext& ctx, float u, float& pmf,
                               float* soleInfinitePmf) const {
  pmf = 0;
  float root;
  const float total = topTotal(ctx, root);
  const bool sole = infinite_.size() == 1;
  // pmfTop's numbers for the one infinite light: its importance over the same total, or 0.
  if (soleInfinitePmf) *soleInfinitePmf = sole ? 0.0f : -1.0f;
  if (!(total > 0) || !std::isfinite(total)) return -1;
  // The top level: the infinite lights, then the tree, by their weights.
  float target = u * total, before = 0;
  for (size_t i = 0; i < infinite_.size(); ++i) {
    const float w = infinite_[i].importance(ctx);
    if (sole && soleInfinitePmf) *soleInfinitePmf = w / total;
    if (target < before + w || (nodes_.empty() && i + 1 == infinite_.size() && w > 0)) {
      pmf = w / total;
      return infiniteLight_[i];
    }
    before += w;
  }
  if (nodes_.empty()) return -1;
  if (!(root > 0)) return -1;
  float p = root / total;
  u = std::min((target - before) / root, kOneMinusEpsilon);
  u = std::max(u, 0.0f);
  const int light = descendAny(ctx, u, p);
  pmf = p;
  return light;
}

float BvhLightSampler::pmfTop(const LightSampleContext& ctx, int light) const {
  if (light < 0 || size_t(light) >= trail_.size()) return 0.0f;
  float root;
  const float total = topTotal(ctx, root);
  if (!(total > 0) || !std::isfinite(total)) return 0.0f;
  if (infiniteSlot_[size_t(light)] >= 0)
    return infinite_[size_t(infiniteSlot_[size_t(light)])].importance(ctx) / total;
  if (!inTree_[size_t(light)]) return 0.0f;
  return pmfAny(ctx, trail_[size_t(light)], root / total);
}

int BvhLightSampler::descendAny(const LightSampleContext& ctx, float u, float& p) const {
  return descend<false>(ctx, u, p);
}

float BvhLightSampler::pmfAny(const LightSampleContext& ctx, uint64_t trail, float p) const {
  return pmfInTree<false>(ctx, trail, p);
}

}  // namespace tray
