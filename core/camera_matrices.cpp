#include "core/camera_matrices.h"

#include <cmath>

namespace tray {
namespace {

/// World to camera space with +z forward (column vectors).
Mat4 worldToCameraColumns(const CameraDesc& camera) {
  Mat4 flipZ;
  flipZ.m[2][2] = -1;  // glTF cameras look down -z; OpenEXR's (RenderMan's) down +z
  return flipZ * camera.toWorld.inv;
}

ExrMatrix toImath(const Mat4& columns) {
  ExrMatrix out;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) out[i * 4 + j] = columns.m[j][i];
  return out;
}

}  // namespace

ExrMatrix exrWorldToCamera(const CameraDesc& camera) {
  return toImath(worldToCameraColumns(camera));
}

ExrMatrix exrWorldToNdc(const CameraDesc& camera, int width, int height) {
  const float aspect = float(width) / float(height);  // the image's aspect wins (camera.cpp)
  Mat4 p;                                             // camera space -> homogeneous NDC
  if (camera.type == CameraDesc::Type::kPerspective) {
    // ndc = 0.5 + 0.5 x / (z tan(fov_x / 2)), 0.5 - 0.5 y / (z tan(fov_y / 2)); w = z.
    const float ty = std::tan(0.5f * camera.yfov), tx = ty * aspect;
    p.m[0][0] = 0.5f / tx, p.m[0][2] = 0.5f;
    p.m[1][1] = -0.5f / ty, p.m[1][2] = 0.5f;
    p.m[2][2] = 0, p.m[2][3] = 1;
    p.m[3][2] = 1, p.m[3][3] = 0;
  } else {
    const float ymag = camera.ymag, xmag = ymag * aspect;
    p.m[0][0] = 0.5f / xmag, p.m[0][3] = 0.5f;
    p.m[1][1] = -0.5f / ymag, p.m[1][3] = 0.5f;
  }
  return toImath(p * worldToCameraColumns(camera));
}

}  // namespace tray
