// Box sampling for emitters (core/shape.h's sampling interface): faces by area.
#include "shapes/box.h"

namespace tray {

void Box::faceAreas(const Transform& toWorld, float out[6]) const {
  const Vec3 size = hi_ - lo_;
  for (int axis = 0; axis < 3; ++axis) {
    const float objectArea = size[(axis + 1) % 3] * size[(axis + 2) % 3];
    Vec3 n(0.0f);
    n[axis] = 1.0f;
    // Opposite faces scale alike under an affine map.
    out[2 * axis] = out[2 * axis + 1] = objectArea * areaScale(toWorld, n);
  }
}

float Box::area(const Transform& toWorld) const {
  float a[6];
  faceAreas(toWorld, a);
  return a[0] + a[1] + a[2] + a[3] + a[4] + a[5];
}

std::optional<ShapeSample> Box::sampleArea(const Transform& toWorld, Vec2 u) const {
  float a[6];
  faceAreas(toWorld, a);
  const float total = a[0] + a[1] + a[2] + a[3] + a[4] + a[5];
  if (!(total > 0) || !std::isfinite(total)) return std::nullopt;
  // Choose the face with u.x and reuse what is left of it (pbrt-v4 A.1's remapping).
  float target = u.x * total;
  int face = 0;
  while (face < 5 && target >= a[face]) target -= a[face++];
  const float ux = std::min(a[face] > 0 ? target / a[face] : 0.0f, 0.99999994f);
  const int axis = face / 2;
  const float sign = face % 2 ? 1.0f : -1.0f;
  const int i = (axis + 1) % 3, j = (axis + 2) % 3;
  Vec3 p, n(0.0f);
  p[axis] = sign > 0 ? hi_[axis] : lo_[axis];
  p[i] = lo_[i] + ux * (hi_[i] - lo_[i]);
  p[j] = lo_[j] + u.y * (hi_[j] - lo_[j]);
  n[axis] = sign;
  ShapeSample s;
  s.p = toWorld.point(p);
  s.n = normalize(toWorld.normal(n));
  s.pdf = 1.0f / total;
  return s;
}

}  // namespace tray
