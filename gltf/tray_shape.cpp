#include "gltf/tray_shape.h"

#include "gltf/gltf_value.h"
#include "gltf/tray_csg.h"
#include "shapes/box.h"
#include "shapes/plane.h"
#include "shapes/sphere.h"

namespace tray {

namespace {

std::shared_ptr<const Shape> parseSphere(ExtensionReader& r) {
  double radius = r.number("radius", 1.0);
  if (!(radius > 0)) r.fail("'radius' must be positive");
  return std::make_shared<Sphere>(float(radius));
}

std::shared_ptr<const Shape> parseBox(ExtensionReader& r) {
  Vec3 lo = r.vec3("min", Vec3(-1.0f)), hi = r.vec3("max", Vec3(1.0f));
  if (!(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z))
    r.fail("'min' must be below 'max' on every axis");
  return std::make_shared<Box>(lo, hi);
}

}  // namespace

TrayShape parseTrayShape(const GltfContext& ctx, const tinygltf::Value& value,
                         const std::string& where) {
  ExtensionReader r(ctx, value, where + " TRAY_shape");
  TrayShape out;
  std::string type = r.string("type", "");
  if (type == "sphere") {
    out.shape = parseSphere(r);
  } else if (type == "plane") {
    out.shape = std::make_shared<Plane>();
  } else if (type == "box") {
    out.shape = parseBox(r);
  } else if (type == "csg") {
    out.shape = parseCsg(ctx, value, r, where);
  } else {
    r.fail(type.empty() ? "has no 'type'" : "has unknown TRAY_shape type '" + type + "'");
  }
  out.material = r.integer("material", -1);
  if (out.material < -1 || out.material >= int(ctx.model.materials.size()))
    r.fail("refers to missing material " + std::to_string(out.material));
  r.finish();
  return out;
}

}  // namespace tray
