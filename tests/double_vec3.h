#pragma once
// A double-precision 3-vector for tests' independent references (ray optics, distance
// functions, solvers checked against TRay's float code): kept apart from core/math.h so that
// a reference shares no arithmetic with what it checks.
#include <cmath>

namespace tray::test {

struct DVec3 {
  double x, y, z;
};
inline DVec3 operator+(DVec3 a, DVec3 b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
inline DVec3 operator-(DVec3 a, DVec3 b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
inline DVec3 operator*(double s, DVec3 a) {
  return {s * a.x, s * a.y, s * a.z};
}
inline double dot(DVec3 a, DVec3 b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline double len(DVec3 a) {
  return std::sqrt(dot(a, a));
}
inline DVec3 unit(DVec3 a) {
  return (1.0 / len(a)) * a;
}
inline DVec3 cross(DVec3 a, DVec3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

}  // namespace tray::test
