#include "core/motion.h"

#include <algorithm>
#include <cmath>

namespace tray {

void timeSegment(size_t count, float t, size_t& segment, float& fraction) {
  // Embree's getTimeSegment: the segment index clamped to the valid ones, the fraction
  // measured from its start (so t = 1 is the end of the last segment).
  const float segments = float(count - 1);
  const float scaled = std::clamp(t, 0.0f, 1.0f) * segments;
  const float index = std::clamp(std::floor(scaled), 0.0f, segments - 1.0f);
  segment = size_t(index);
  fraction = scaled - index;
}

Vec3 deformedVertexAt(const TriangleMesh& mesh, uint32_t v, float t) {
  size_t k;
  float f;
  timeSegment(mesh.positionSteps.size(), t, k, f);
  return (1.0f - f) * mesh.positionSteps[k][v] + f * mesh.positionSteps[k + 1][v];
}

Mat4 interpolateSteps(const std::vector<Mat4>& steps, float t) {
  if (steps.size() == 1) return steps[0];
  size_t k;
  float f;
  timeSegment(steps.size(), t, k, f);
  const Mat4& a = steps[k];
  const Mat4& b = steps[k + 1];
  Mat4 m;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) m.m[r][c] = (1.0f - f) * a.m[r][c] + f * b.m[r][c];
  return m;  // the last row stays 0 0 0 1: the steps are affine
}

const Transform* movedPlacementAt(const Primitive& p, float t, Transform& moved) {
  moved.m = interpolateSteps(p.motion, t);
  return invert(moved.m, moved.inv) ? &moved : nullptr;
}

Bounds3 motionBounds(const Primitive& p, const Bounds3& local) {
  if (p.motion.empty()) return p.toWorld.bounds(local);
  Bounds3 b;
  for (const Mat4& step : p.motion) {
    Transform t;
    t.m = step;  // bounds() reads the matrix only; a step may be singular
    b.extend(t.bounds(local));
  }
  return b;
}

bool stepsMove(const std::vector<Mat4>& steps) {
  for (const Mat4& s : steps)
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c)
        if (!(s.m[r][c] == steps[0].m[r][c])) return true;
  return false;
}

}  // namespace tray
