#include "gltf/gltf_cameras_lights.h"

#include <cmath>

#include "gltf/gltf_value.h"

namespace tray {

namespace {

/// Finite in single precision, which TRay stores these values in.
bool finite(double v) {
  return std::isfinite(float(v));
}

}  // namespace

CameraDesc convertCamera(const GltfContext& ctx, int index) {
  const tinygltf::Camera& g = ctx.model.cameras[size_t(index)];
  const std::string where = nameOf("camera", index, g.name);
  CameraDesc c;
  c.name = g.name;
  if (g.type == "perspective") {
    const auto& p = g.perspective;
    c.type = CameraDesc::Type::kPerspective;
    if (!finite(p.yfov) || p.yfov <= 0 || p.yfov >= kPi)
      ctx.fail(where + " yfov must be a finite angle in (0, pi)");
    if (!finite(p.znear) || p.znear <= 0) ctx.fail(where + " znear must be finite and positive");
    if (!finite(p.aspectRatio) || p.aspectRatio < 0)
      ctx.fail(where + " aspectRatio must be finite and positive");
    if (!finite(p.zfar) || (p.zfar != 0 && p.zfar <= p.znear))
      ctx.fail(where + " zfar must be finite and beyond znear");
    c.yfov = float(p.yfov);
    c.aspectRatio = float(p.aspectRatio);  // 0 when the file leaves it out
    c.znear = float(p.znear);
  } else if (g.type == "orthographic") {
    const auto& o = g.orthographic;
    c.type = CameraDesc::Type::kOrthographic;
    if (!finite(o.xmag) || !finite(o.ymag) || o.xmag == 0 || o.ymag == 0)
      ctx.fail(where + " xmag and ymag must be finite and non-zero");
    if (!finite(o.znear) || o.znear < 0) ctx.fail(where + " znear must be finite and >= 0");
    if (!finite(o.zfar) || o.zfar <= o.znear)
      ctx.fail(where + " zfar must be finite and beyond znear");
    c.xmag = float(o.xmag);
    c.ymag = float(o.ymag);
    c.znear = float(o.znear);
  } else {
    ctx.fail(where + " has unknown type '" + g.type + "'");
  }
  if (const tinygltf::Value* ext = findExtension(g.extensions, "TRAY_camera")) {
    // The thin lens (docs/scene-format.md, "Depth of field"); --lens-radius, --focus-distance
    // and --aperture-blades override it.
    ExtensionReader r(ctx, *ext, where + " TRAY_camera");
    c.lensRadius = float(r.number("lensRadius", 0.0, 0.0, 1e30));
    c.focusDistance = float(r.number("focusDistance", 0.0, 0.0, 1e30));
    c.apertureBlades = r.integer("apertureBlades", 0);
    if (c.apertureBlades != 0 && (c.apertureBlades < 3 || c.apertureBlades > 64))
      r.fail("apertureBlades " + std::to_string(c.apertureBlades) +
             ": expected 0 (round) or 3..64");
    if (c.lensRadius > 0 && !(c.focusDistance > 0))
      r.fail("lensRadius > 0 needs a focusDistance > 0");
    r.finish();
  }
  return c;
}

PunctualLightDesc convertLight(const GltfContext& ctx, int index) {
  const tinygltf::Light& g = ctx.model.lights[size_t(index)];
  const std::string where = nameOf("light", index, g.name);
  PunctualLightDesc l;
  if (g.type == "point") {
    l.type = PunctualLightDesc::Type::kPoint;
  } else if (g.type == "spot") {
    l.type = PunctualLightDesc::Type::kSpot;
  } else if (g.type == "directional") {
    l.type = PunctualLightDesc::Type::kDirectional;
  } else {
    ctx.fail(where + " has unknown type '" + g.type + "'");
  }
  Color color(1.0f);
  if (!g.color.empty()) {
    if (g.color.size() != 3) ctx.fail(where + " color needs 3 numbers");
    for (double v : g.color)
      if (!finite(v) || v < 0) ctx.fail(where + " color must be finite and non-negative");
    color = {float(g.color[0]), float(g.color[1]), float(g.color[2])};
  }
  if (!finite(g.intensity) || g.intensity < 0)
    ctx.fail(where + " intensity must be finite and non-negative");
  l.intensity = color * float(g.intensity);
  if (l.type == PunctualLightDesc::Type::kSpot) {
    double inner = g.spot.innerConeAngle, outer = g.spot.outerConeAngle;
    // KHR_lights_punctual: 0 <= inner < outer <= pi/2.
    if (!finite(inner) || !finite(outer) || inner < 0 || inner >= outer || outer > kPi / 2 + 1e-6)
      ctx.fail(where + " cone angles must satisfy 0 <= inner < outer <= pi/2");
    l.innerConeAngle = float(inner);
    l.outerConeAngle = float(outer);
  }
  return l;
}

}  // namespace tray
