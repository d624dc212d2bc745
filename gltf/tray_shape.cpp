#include "gltf/tray_shape.h"

#include "gltf/gltf_value.h"
#include "gltf/tray_csg.h"
#include "gltf/tray_curves.h"
#include "shapes/box.h"
#include "shapes/plane.h"
#include "shapes/quadric.h"
#include "shapes/sphere.h"
#include "shapes/torus.h"

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

std::shared_ptr<const Shape> parseTorus(ExtensionReader& r) {
  double R = r.number("majorRadius", 1.0), minor = r.number("minorRadius", 0.25);
  if (!(minor > 0 && R > minor)) r.fail("needs 'majorRadius' > 'minorRadius' > 0");
  return std::make_shared<Torus>(float(R), float(minor));
}

std::shared_ptr<const Shape> parseQuadric(ExtensionReader& r, Quadric::Kind kind) {
  double radius = r.number("radius", 1.0), height = r.number("height", 1.0);
  if (!(radius > 0)) r.fail("'radius' must be positive");
  if (!(height > 0)) r.fail("'height' must be positive");
  double waist = 0;
  if (kind == Quadric::Kind::kHyperboloid) {
    waist = r.number("waist", 0.5 * radius);
    if (!(waist >= 0 && waist < radius)) r.fail("'waist' must be in [0, radius)");
  }
  return std::make_shared<Quadric>(kind, float(radius), float(height), r.boolean("capped", false),
                                   float(waist));
}

std::shared_ptr<const Shape> parseDisk(ExtensionReader& r) {
  double radius = r.number("radius", 1.0), inner = r.number("innerRadius", 0.0);
  if (!(radius > 0)) r.fail("'radius' must be positive");
  if (!(inner >= 0 && inner < radius)) r.fail("'innerRadius' must be in [0, radius)");
  return std::make_shared<Disk>(float(radius), float(inner));
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
  } else if (type == "torus") {
    out.shape = parseTorus(r);
  } else if (type == "cylinder") {
    out.shape = parseQuadric(r, Quadric::Kind::kCylinder);
  } else if (type == "cone") {
    out.shape = parseQuadric(r, Quadric::Kind::kCone);
  } else if (type == "paraboloid") {
    out.shape = parseQuadric(r, Quadric::Kind::kParaboloid);
  } else if (type == "hyperboloid") {
    out.shape = parseQuadric(r, Quadric::Kind::kHyperboloid);
  } else if (type == "disk") {
    out.shape = parseDisk(r);
  } else if (type == "curves") {
    out.shape = parseCurves(ctx, r);
  } else if (type == "subdivision") {
    out.shape = parseSubdivision(ctx, r);
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
