#include "accel/bvh_top_level.h"

#include <tbb/parallel_for.h>

#include "core/motion.h"

namespace tray {

TopLevel buildTopLevel(const Scene& scene, const std::vector<std::unique_ptr<MeshBvh>>& meshes,
                       const TwoLevelOptions& options, TwoLevelParts& parts) {
  constexpr uint32_t kArrayGroup = TwoLevelParts::kArrayGroup;
  TopLevel out;
  const auto& prims = scene.primitives;
  // Items (TwoLevelParts::placed): the primitives, then every instance array's instances.
  parts.itemsBase = uint32_t(prims.size());
  size_t items = prims.size();
  for (uint32_t i = 0; i < prims.size(); ++i)
    if (prims[i].instances) {
      parts.arrayFirst.push_back(uint32_t(items));
      parts.arrayPrimitive.push_back(i);
      parts.arraySize.push_back(uint32_t(prims[i].instances->size()));
      items += (prims[i].instances->size() + kArrayGroup - 1) / kArrayGroup;
    }
  parts.itemCount = uint32_t(items);
  std::vector<Bounds3> boxes(items);
  for (size_t a = 0; a < parts.arrayFirst.size(); ++a) {
    const Primitive& p = prims[parts.arrayPrimitive[a]];
    out.arrayBoxes.push_back(instanceBoxes(*p.instances, meshes[p.mesh]->bounds(), kArrayGroup));
    parts.arrayBoxes.push_back(out.arrayBoxes[a].data());
    const uint32_t first = parts.arrayFirst[a];
    const uint32_t groups = (parts.arraySize[a] + kArrayGroup - 1) / kArrayGroup;
    tbb::parallel_for(uint32_t(0), groups, [&](uint32_t g) {
      boxes[first + g] = groupBounds(parts.placed(first + g).boxes, TwoLevelParts::kGroupBoxNodes);
    });
    if (meshes[p.mesh]->bounds().empty()) continue;
    if (!options.hierarchy)
      for (uint32_t g = 0; g < groups; ++g) out.flat.push_back(first + g);
  }
  for (uint32_t i = 0; i < prims.size(); ++i) {
    const Primitive& p = prims[i];
    if (p.instances) continue;  // its instances are items of their own
    if (p.kind == Primitive::Kind::kMesh) {
      Bounds3 b = meshes[p.mesh]->bounds();
      if (!b.empty()) boxes[i] = motionBounds(p, b);  // over the shutter when it moves
    } else {
      Bounds3 b = motionBounds(p, p.shape->bounds());
      if (b.empty()) continue;
      if (!b.finite()) {
        out.unbounded.push_back(i);
      } else {
        boxes[i] = b;
      }
    }
    if (!options.hierarchy && !boxes[i].empty()) out.flat.push_back(i);
  }
  if (!options.hierarchy) return out;
  // One primitive per top leaf: entering an instance costs a transform and a ray set-up,
  // so each is culled by its own box first.
  BvhBuildOptions topOptions = options.build;
  topOptions.maxLeafSize = 1;
  Bvh top = topOptions.builder == BvhBuilder::kBinnedSah
                ? buildBvhBinnedSah(std::move(boxes), topOptions)
                : buildBvh(boxes, topOptions);
  std::vector<Bounds3>().swap(boxes);
  out.sahCost = sahCost(top, options.build);
  out.binaryNodes = top.nodes.size();
  out.tree = collapseToBvh4(std::move(top));
  // One placed primitive (a single mesh, say): its own tree culls, the top tree adds nothing.
  if (out.tree.primitives.size() == 1) out.single = out.tree.primitives[0];
  return out;
}

}  // namespace tray
