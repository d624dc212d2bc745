// The seed's first accelerator: none. Every ray tests every primitive and every triangle, so
// render time grows with the triangle count; kept for small scenes and to measure what the
// hierarchies buy (bench/accel_bench.cpp).
#include "accel/bvh_accelerator.h"

namespace tray {

std::unique_ptr<Accelerator> makeNaiveAccelerator(const Scene& scene) {
  TwoLevelOptions o;
  o.hierarchy = false;
  return makeTwoLevelAccelerator(scene, o);
}

}  // namespace tray
