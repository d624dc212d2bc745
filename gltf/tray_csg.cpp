#include "gltf/tray_csg.h"

#include <algorithm>

#include "accel/registry.h"
#include "core/error.h"
#include "gltf/gltf_meshes.h"
#include "gltf/gltf_scene_graph.h"
#include "gltf/tray_shape.h"
#include "shapes/mesh_solid.h"

namespace tray {
namespace {

constexpr size_t kMaxCsgDepth = 64;  // nested CSG nodes; deeper trees are refused, not recursed

/// The operand node indices of a csg TRAY_shape, checked to exist.
std::vector<int> operandNodes(const GltfContext& ctx, ExtensionReader& r) {
  const tinygltf::Value* list = r.value("children");
  if (!list || !list->IsArray() || list->ArrayLen() == 0)
    r.fail("needs 'children': a non-empty array of node indices");
  std::vector<int> nodes;
  for (size_t i = 0; i < list->ArrayLen(); ++i) {
    const tinygltf::Value& v = list->Get(int(i));
    double d = v.IsNumber() ? v.GetNumberAsDouble() : -1.0;
    if (!(d >= 0 && d < double(ctx.model.nodes.size()) && d == double(int(d))))
      r.fail("'children'[" + std::to_string(i) + "] is not a node index");
    nodes.push_back(int(d));
  }
  return nodes;
}

/// Is node `index` listed as an operand by some csg TRAY_shape in the file?
bool isOperand(const GltfContext& ctx, int index) {
  for (const auto& node : ctx.model.nodes) {
    const tinygltf::Value* ext = findExtension(node.extensions, "TRAY_shape");
    if (!ext || !ext->IsObject() || !ext->Has("children") || !ext->Get("children").IsArray())
      continue;
    const tinygltf::Value& list = ext->Get("children");
    for (size_t i = 0; i < list.ArrayLen(); ++i)
      if (list.Get(int(i)).IsNumber() && list.Get(int(i)).GetNumberAsDouble() == double(index))
        return true;
  }
  return false;
}

/// A glTF mesh as one closed solid: its triangle primitives merged, the first one's material.
std::shared_ptr<const Shape> meshSolid(const GltfContext& ctx, int meshIndex, int& material) {
  MeshStats stats;
  std::vector<TriangleMesh> parts = convertMesh(ctx, meshIndex, -1, stats);
  if (parts.empty()) ctx.fail(nameOf("mesh", meshIndex) + " used in CSG has no triangles");
  TriangleMesh merged = std::move(parts[0]);
  merged.name = nameOf("mesh", meshIndex, ctx.model.meshes[size_t(meshIndex)].name);
  merged.normals.clear(), merged.tangents.clear(), merged.tangentSigns.clear();
  for (size_t k = 1; k < parts.size(); ++k) {
    uint32_t base = uint32_t(merged.positions.size());
    merged.positions.insert(merged.positions.end(), parts[k].positions.begin(),
                            parts[k].positions.end());
    for (uint32_t i : parts[k].indices) merged.indices.push_back(base + i);
  }
  if (merged.uvs.size() != merged.positions.size()) merged.uvs.clear();
  material = merged.material;
  try {
    return std::make_shared<MeshSolid>(std::move(merged), acceleratorFactory("embree"));
  } catch (const Error& e) {
    ctx.fail(e.what());
  }
}

std::shared_ptr<const Csg> parseNode(const GltfContext& ctx, ExtensionReader& r,
                                     const std::string& where, const std::string& name,
                                     std::vector<int>& path);

/// One operand: a node placed in the CSG node's space by its own local transform.
CsgChild parseOperand(const GltfContext& ctx, int index, const std::string& parentWhere,
                      std::vector<int>& path) {
  const auto& node = ctx.model.nodes[size_t(index)];
  const std::string where = nameOf("node", index, node.name);
  if (std::find(path.begin(), path.end(), index) != path.end())
    ctx.fail(parentWhere + " TRAY_shape csg contains itself through " + where);
  if (path.size() >= kMaxCsgDepth) ctx.fail(where + " nests CSG deeper than 64 levels");
  if (!node.children.empty())
    ctx.fail(where + " is a CSG operand and cannot have glTF children (nest a csg instead)");
  CsgChild c;
  c.name = node.name.empty() ? where : node.name;
  Mat4 m = localMatrix(ctx, index), inv;
  if (!invert(m, inv)) ctx.fail(where + " is a CSG operand with a singular transform");
  c.toCsg = Transform(m);
  if (const tinygltf::Value* ext = findExtension(node.extensions, "TRAY_shape")) {
    if (ext->IsObject() && ext->Has("type") && ext->Get("type").IsString() &&
        ext->Get("type").Get<std::string>() == "csg") {
      ExtensionReader nested(ctx, *ext, where + " TRAY_shape");
      nested.string("type", "");  // "csg", checked above
      path.push_back(index);
      c.shape = parseNode(ctx, nested, where, c.name, path);
      path.pop_back();
      c.material = nested.integer("material", -1);
      nested.finish();
    } else {
      TrayShape s = parseTrayShape(ctx, *ext, where);
      if (!s.shape->isSolid())
        ctx.fail(where +
                 " is a CSG operand but its TRAY_shape is an open surface, not a solid"
                 " (a disk, or a quadric without \"capped\": true)");
      c.shape = s.shape;
      c.material = s.material;
    }
  } else if (node.mesh >= 0) {
    c.shape = meshSolid(ctx, node.mesh, c.material);
  } else {
    ctx.fail(where + " is a CSG operand but has neither a TRAY_shape nor a mesh");
  }
  return c;
}

std::shared_ptr<const Csg> parseNode(const GltfContext& ctx, ExtensionReader& r,
                                     const std::string& where, const std::string& name,
                                     std::vector<int>& path) {
  CsgOp op{};
  std::string opName = r.string("op", "");
  try {
    op = csgOpFromName(opName);
  } catch (const Error& e) {
    r.fail(e.what());
  }
  std::vector<CsgChild> children;
  for (int index : operandNodes(ctx, r)) children.push_back(parseOperand(ctx, index, where, path));
  return std::make_shared<Csg>(op, std::move(children), name);
}

}  // namespace

std::shared_ptr<const Csg> parseCsg(const GltfContext& ctx, const tinygltf::Value& value,
                                    ExtensionReader& r, const std::string& where) {
  int self = -1;  // which node this is: the TRAY_shape value lives inside it
  for (size_t i = 0; i < ctx.model.nodes.size(); ++i)
    if (findExtension(ctx.model.nodes[i].extensions, "TRAY_shape") == &value) self = int(i);
  std::vector<int> path;
  std::string name = where;
  if (self >= 0) {
    path.push_back(self);
    if (!ctx.model.nodes[size_t(self)].name.empty()) name = ctx.model.nodes[size_t(self)].name;
  }
  std::shared_ptr<const Csg> csg = parseNode(ctx, r, where, name, path);
  if (!csg->bounded() && !(self >= 0 && isOperand(ctx, self))) {
    try {
      csg->requireBounded();
    } catch (const Error& e) {
      ctx.fail(e.what());
    }
  }
  return csg;
}

}  // namespace tray
