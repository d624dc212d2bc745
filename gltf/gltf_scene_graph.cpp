#include "gltf/gltf_scene_graph.h"

#include <cmath>

#include "core/error.h"
#include "gltf/gltf_cameras_lights.h"
#include "gltf/gltf_value.h"
#include "gltf/tray_shape.h"

namespace tray {

namespace {

void checkNumbers(const GltfContext& ctx, const std::vector<double>& v, size_t size,
                  const std::string& what) {
  if (v.size() != size) ctx.fail(what + " needs " + std::to_string(size) + " numbers");
  // Checked in single precision, which TRay computes in: 1e300 is finite only as a double.
  for (double d : v)
    if (!std::isfinite(float(d))) ctx.fail(what + " contains NaN or infinity");
}

/// The light a node carries through KHR_lights_punctual, or -1.
int nodeLight(const GltfContext& ctx, int index) {
  const auto& node = ctx.model.nodes[size_t(index)];
  const tinygltf::Value* ext = findExtension(node.extensions, "KHR_lights_punctual");
  if (!ext) return -1;
  ExtensionReader r(ctx, *ext, nameOf("node", index, node.name) + " KHR_lights_punctual");
  int light = r.integer("light", -1);
  if (light < 0 || size_t(light) >= ctx.model.lights.size())
    r.fail("refers to missing light " + std::to_string(light));
  return light;
}

Environment sceneEnvironment(const GltfContext& ctx, int sceneIndex) {
  const auto& s = ctx.model.scenes[size_t(sceneIndex)];
  Environment env;
  const tinygltf::Value* ext = findExtension(s.extensions, "TRAY_environment");
  if (!ext) return env;
  ExtensionReader r(ctx, *ext, nameOf("scene", sceneIndex, s.name) + " TRAY_environment");
  env.ambient = r.vec3("ambient", env.ambient, 0.0);
  env.background = r.vec3("background", env.background, 0.0);
  env.transparent = r.boolean("transparent", env.transparent);
  // "image": a path relative to the glTF file, or a glTF image index; loaded for the chosen
  // scene only (gltf/gltf_environment.cpp).
  if (const tinygltf::Value* image = r.value("image")) {
    if (image->IsString() && !image->Get<std::string>().empty())
      env.imagePath = image->Get<std::string>();
    else if (image->IsInt() && image->Get<int>() >= 0 &&
             size_t(image->Get<int>()) < ctx.model.images.size())
      env.imageIndex = image->Get<int>();
    else
      r.fail("image must be a file path or the index of one of the document's images");
  }
  env.rotation = float(r.number("rotation", 0.0, -36000, 36000));
  env.intensity = float(r.number("intensity", 1.0, 0, 1e30));
  r.finish();
  return env;
}

/// A node's world transform as a tray::Transform; false if it is singular (a zero scale hides
/// a node, which glTF allows). Overflow to infinity while composing is an error.
bool worldTransform(const GltfContext& ctx, const Mat4& m, const std::string& where,
                    Transform& out) {
  if (!m.isFinite()) ctx.fail(where + " world transform overflows to infinity");
  Mat4 inv;
  if (!invert(m, inv)) return false;
  out = Transform(m);
  return true;
}

/// An EXT_mesh_gpu_instancing instance: its object id and index k in its node (id -1: none).
struct Instance {
  int id = -1;
  size_t k = 0;
};

struct Walker {
  const GltfContext& ctx;
  const ObjectTable& objects;
  int defaultMaterial;
  MeshTable& meshes;
  const Deformer& deformer;
  MeshStats& stats;
  Scene& scene;
  const std::vector<Deformer>* stepDeformers;
  std::vector<int>* instanceNodes;
  int nextInstanceId;
  size_t instanceArrayMin;
  size_t hiddenNodes = 0, hiddenInstances = 0;
  size_t arrayPlacements = 0;  ///< instances placed by instance arrays (the cap counts them)

  /// Motion blur: the vertices of primitive `primitive` of node `node`'s mesh (as read, in `m`)
  /// deformed at each motion step, kept when they differ between steps.
  void deformSteps(int node, size_t primitive, TriangleMesh& m) const {
    if (!stepDeformers) return;
    std::vector<std::vector<Vec3>> steps;
    for (const Deformer& d : *stepDeformers) {
      TriangleMesh step;  // positions only: the deformer leaves absent attributes alone
      step.positions = m.positions;
      d.apply(node, primitive, step);
      steps.push_back(std::move(step.positions));
    }
    for (const auto& s : steps)
      if (s != steps[0]) return void(m.positionSteps = std::move(steps));
  }

  /// A deformed mesh is converted again for this node alone: its vertices depend on the node's
  /// weights and skin. Returns the Scene::meshes indices of its primitives.
  std::vector<uint32_t> convertDeformed(int node, int mesh) {
    MeshStats copy = stats;  // the caps count the copies; the warnings counted the file once
    std::vector<TriangleMesh> converted =
        convertMesh(ctx, mesh, defaultMaterial, copy, [&](size_t primitive, TriangleMesh& m) {
          deformSteps(node, primitive, m);  // from the vertices as read, before the frame's
          deformer.apply(node, primitive, m);
        });
    stats.triangles = copy.triangles, stats.vertices = copy.vertices;
    std::vector<uint32_t> placed;
    for (auto& m : converted) {
      placed.push_back(uint32_t(scene.meshes.size()));
      scene.meshes.push_back(std::move(m));
    }
    return placed;
  }

  /// The node's mesh deforms at the frame's time or, with motion blur, at some motion step.
  bool deformsOverShutter(int node) const {
    if (deformer.deforms(node)) return true;
    if (stepDeformers)
      for (const Deformer& d : *stepDeformers)
        if (d.deforms(node)) return true;
    return false;
  }

  /// The Scene::meshes indices of node `node`'s mesh: stored once for every node that places
  /// it, or converted for this node alone when it deforms.
  std::vector<uint32_t> nodeMeshes(int node, int mesh) {
    if (deformsOverShutter(node)) return convertDeformed(node, mesh);
    if (!meshes.moved[size_t(mesh)]) {
      meshes.moved[size_t(mesh)] = true;
      for (auto& m : meshes.converted[size_t(mesh)]) {
        meshes.placed[size_t(mesh)].push_back(uint32_t(scene.meshes.size()));
        scene.meshes.push_back(std::move(m));
      }
    }
    return meshes.placed[size_t(mesh)];
  }

  /// Places what node `node` carries (a shape, or its mesh's primitives `placed`) at toWorld.
  void place(int node, const TrayShape* shape, const std::vector<uint32_t>& placed,
             const Transform& toWorld, Instance instance = {}) {
    if (shape) {  // a shape replaces the node's mesh, if any
      Primitive p;
      p.kind = Primitive::Kind::kShape;
      p.shape = shape->shape;
      p.material = shape->material >= 0 ? shape->material : defaultMaterial;
      return addPrimitive(node, toWorld, p, instance);
    }
    for (uint32_t m : placed) {
      Primitive p;
      p.kind = Primitive::Kind::kMesh;
      p.mesh = m;
      p.material = scene.meshes[m].material;
      addPrimitive(node, toWorld, p, instance);
    }
  }

  void addPrimitive(int node, const Transform& toWorld, Primitive& p, const Instance& instance) {
    if (scene.primitives.size() + arrayPlacements >= kMaxPrimitives)
      ctx.fail("the scene places more than " + std::to_string(kMaxPrimitives) +
               " objects (node and mesh primitive instances)");
    p.toWorld = toWorld;
    p.objectId = instance.id >= 0 ? instance.id : node;
    p.name = instance.id >= 0 ? instanceName(node, instance.k) : ctx.model.nodes[size_t(node)].name;
    scene.primitives.push_back(std::move(p));
    if (instanceNodes) instanceNodes->push_back(instance.id >= 0 ? node : -1);
  }

  /// EXT_mesh_gpu_instancing: "<node name>#k", or "node<index>#k" for an unnamed node.
  std::string instanceName(int node, size_t k) const {
    std::string name = ctx.model.nodes[size_t(node)].name;
    if (name.empty()) name = "node" + std::to_string(node);
    name += '#';
    name += std::to_string(k);
    return name;
  }

  /// Every instance of node `index` (EXT_mesh_gpu_instancing) at world * its local matrix,
  /// each with an object id of its own after the node indices (docs/instancing.md).
  void placeInstances(int index, const Mat4& world, const InstanceAttributes& instances,
                      const TrayShape* shape, const std::vector<uint32_t>& placed) {
    const std::string where = nameOf("node", index, ctx.model.nodes[size_t(index)].name);
    const size_t perInstance = shape ? 1 : placed.size();
    // One allocation for all of them: growing by doubling would briefly hold 1.5x to 2x.
    const size_t needed = scene.primitives.size() + instances.count * perInstance;
    if (needed > scene.primitives.capacity() && needed <= kMaxPrimitives)
      scene.primitives.reserve(needed);
    forEachInstance(ctx, instances, where, [&](size_t k, const Mat4& local) {
      Transform toWorld;
      const int id = nextInstanceId++;
      const Mat4 m = world * local;
      if (!m.isFinite())  // named here: a message built per instance would cost 10^6 strings
        ctx.fail(where + " instance " + std::to_string(k) + " world transform overflows");
      if (!worldTransform(ctx, m, where, toWorld))
        return void(++hiddenInstances);  // a zero scale hides the instance
      place(index, shape, placed, toWorld, {id, k});
    });
  }

  /// Whether node `index`'s instances are placed as instance arrays: enough of them, the load
  /// poses no motion (instanceNodes is asked for then), and every mesh primitive is opaque
  /// (alpha filters name a placed primitive) and not emissive (lights are per instance).
  bool asArray(const InstanceAttributes& instances, const TrayShape* shape,
               const std::vector<uint32_t>& placed) const {
    if (shape || instanceNodes || stepDeformers || instanceArrayMin == 0 ||
        instances.count < instanceArrayMin)
      return false;
    for (uint32_t m : placed) {
      const int mat = scene.meshes[m].material;
      // The default material (appended after the walk) is opaque and black.
      if (mat < 0 || size_t(mat) >= scene.materials.size()) continue;
      const Material& material = scene.materials[size_t(mat)];
      if (material.alphaMode != AlphaMode::kOpaque || !isBlack(material.emissive) ||
          material.emissiveTexture.valid())
        return false;
    }
    return true;
  }

  /// Every instance of node `index` as one instance array shared by its mesh's primitives: ids
  /// and names as placeInstances gives them, a zero-scale instance skipped (its id unused).
  void placeArray(int index, const Mat4& world, const InstanceAttributes& instances,
                  const std::vector<uint32_t>& placed) {
    const auto& node = ctx.model.nodes[size_t(index)];
    const std::string where = nameOf("node", index, node.name);
    auto array = std::make_shared<InstanceArray>();
    array->firstObjectId = nextInstanceId;
    nextInstanceId += int(instances.count);
    array->name = node.name.empty() ? "node" + std::to_string(index) : node.name;
    // The local matrices first, in place of the world-to-object ones (no second array).
    std::vector<Affine3>& slots = array->worldToObject;
    composeInstanceMatrices(ctx, instances, where, slots);
    size_t kept = 0;
    for (size_t k = 0; k < slots.size(); ++k) {
      if (scene.primitives.size() + arrayPlacements + placed.size() > kMaxPrimitives)
        ctx.fail("the scene places more than " + std::to_string(kMaxPrimitives) +
                 " objects (node and mesh primitive instances)");
      const Mat4 m = world * mat4Of(slots[k]);
      if (!m.isFinite())
        ctx.fail(where + " instance " + std::to_string(k) + " world transform overflows");
      Mat4 inv;  // as Transform(m) inverts (core/transform.cpp)
      if (!invert(m, inv)) {
        ++hiddenInstances;  // a zero scale hides the instance
        continue;
      }
      if (kept != k && array->indexInNode.empty())  // the first skipped: note every index
        for (uint32_t j = 0; j < kept; ++j) array->indexInNode.push_back(j);
      if (!array->indexInNode.empty()) array->indexInNode.push_back(uint32_t(k));
      slots[kept++] = affineOf(inv);
      arrayPlacements += placed.size();
    }
    if (kept == 0) return;
    if (kept < slots.size()) slots.resize(kept), slots.shrink_to_fit();
    for (uint32_t m : placed) {
      Primitive p;
      p.kind = Primitive::Kind::kMesh;
      p.mesh = m;
      p.material = scene.meshes[m].material;
      p.objectId = index;
      p.name = node.name;
      p.instances = array;
      scene.primitives.push_back(std::move(p));
    }
  }

  void visit(int index, const Mat4& world) {
    const auto& node = ctx.model.nodes[size_t(index)];
    const std::string where = nameOf("node", index, node.name);
    Transform toWorld;
    bool invertible = worldTransform(ctx, world, where, toWorld);
    if (node.camera >= 0) {
      if (!invertible) ctx.fail(where + " places a camera with a singular transform");
      CameraDesc c = objects.cameras[size_t(node.camera)];
      if (c.name.empty()) c.name = node.name;
      c.nodeName = node.name;
      c.gltfIndex = node.camera;  // --camera N means the file's cameras[N] (docs/scene-format.md)
      c.node = index;
      c.toWorld = toWorld;
      scene.cameras.push_back(c);
    }
    if (int l = objects.nodeLights[size_t(index)]; l >= 0) {
      PunctualLightDesc light = objects.lights[size_t(l)];
      // Lights sit at the node's origin and shine down its local -Z (KHR_lights_punctual).
      light.position = {world.m[0][3], world.m[1][3], world.m[2][3]};
      Vec3 d{-world.m[0][2], -world.m[1][2], -world.m[2][2]};
      if (!(length(d) > 0)) ctx.fail(where + " places a light with a degenerate direction");
      light.direction = normalize(d);
      scene.lights.push_back(light);
    }
    const std::optional<TrayShape>& shape = objects.shapes[size_t(index)];
    if (!shape && node.mesh < 0) return;
    static const std::vector<uint32_t> none;
    const TrayShape* s = shape ? &*shape : nullptr;
    // A skinned mesh ignores its node's transform (glTF 2.0 §3.7.3.3), singular or not.
    const bool skinned = !shape && deformer.skinned(index);
    const std::optional<InstanceAttributes>& instances = objects.instancing[size_t(index)];
    if (instances && skinned)
      ctx.fail(where + " EXT_mesh_gpu_instancing on a skinned mesh is not supported");
    if (instances) {
      const std::vector<uint32_t>& placed = s ? none : nodeMeshes(index, node.mesh);
      if (asArray(*instances, s, placed)) return placeArray(index, world, *instances, placed);
      return placeInstances(index, world, *instances, s, placed);
    }
    if (!invertible && !skinned) return void(++hiddenNodes);
    // A skinned mesh converted for this node alone is in world space already.
    const bool worldSpace = skinned && deformsOverShutter(index);
    place(index, s, s ? none : nodeMeshes(index, node.mesh), worldSpace ? Transform() : toWorld);
  }
};

}  // namespace

Mat4 localMatrix(const GltfContext& ctx, int index) {
  const auto& n = ctx.model.nodes[size_t(index)];
  const std::string where = nameOf("node", index, n.name);
  if (!n.matrix.empty()) {
    // glTF 2.0 §3.5.2: a matrix excludes TRS, and must be affine (last row 0 0 0 1).
    checkNumbers(ctx, n.matrix, 16, where + " matrix");
    Mat4 m = Mat4::fromColumnMajor(n.matrix.data());
    if (!m.isFinite()) ctx.fail(where + " matrix overflows single precision");
    if (std::fabs(m.m[3][0]) > 1e-6f || std::fabs(m.m[3][1]) > 1e-6f ||
        std::fabs(m.m[3][2]) > 1e-6f || std::fabs(m.m[3][3] - 1) > 1e-6f)
      ctx.fail(where + " matrix is not affine (last row must be 0 0 0 1)");
    return m;
  }
  Mat4 t, r, s;
  if (!n.translation.empty()) {
    checkNumbers(ctx, n.translation, 3, where + " translation");
    t = Mat4::translate(
        {float(n.translation[0]), float(n.translation[1]), float(n.translation[2])});
  }
  if (!n.rotation.empty()) {
    checkNumbers(ctx, n.rotation, 4, where + " rotation");
    const auto& q = n.rotation;
    double len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (!(len > 0) || !std::isfinite(len)) ctx.fail(where + " rotation is not a unit quaternion");
    // Exporters write quaternions rounded to a few digits: renormalise rather than refuse.
    r = Mat4::rotate(float(q[0] / len), float(q[1] / len), float(q[2] / len), float(q[3] / len));
  }
  if (!n.scale.empty()) {
    checkNumbers(ctx, n.scale, 3, where + " scale");
    s = Mat4::scale({float(n.scale[0]), float(n.scale[1]), float(n.scale[2])});
  }
  Mat4 m = t * r * s;  // glTF 2.0 §3.5.2: M = T * R * S
  if (!m.isFinite()) ctx.fail(where + " transform overflows to infinity");
  return m;
}

ObjectTable convertObjects(const GltfContext& ctx) {
  const auto& model = ctx.model;
  ObjectTable t;
  for (size_t i = 0; i < model.cameras.size(); ++i) t.cameras.push_back(convertCamera(ctx, int(i)));
  for (size_t i = 0; i < model.lights.size(); ++i) t.lights.push_back(convertLight(ctx, int(i)));
  for (size_t i = 0; i < model.nodes.size(); ++i) {
    t.localMatrices.push_back(localMatrix(ctx, int(i)));
    t.nodeLights.push_back(nodeLight(ctx, int(i)));
    const auto& node = model.nodes[i];
    const tinygltf::Value* ext = findExtension(node.extensions, "TRAY_shape");
    t.shapes.push_back(
        ext ? std::optional(parseTrayShape(ctx, *ext, nameOf("node", int(i), node.name)))
            : std::nullopt);
    t.instancing.push_back(parseInstancing(ctx, int(i)));
  }
  for (size_t i = 0; i < model.scenes.size(); ++i)
    t.environments.push_back(sceneEnvironment(ctx, int(i)));
  return t;
}

void addSceneNodes(const GltfContext& ctx, const ObjectTable& objects, int sceneIndex,
                   int defaultMaterial, MeshTable& meshes, const Deformer& deformer,
                   MeshStats& stats, Scene& scene, const std::vector<Deformer>* stepDeformers,
                   std::vector<int>* instanceNodes, size_t instanceArrayMin) {
  if (instanceNodes) instanceNodes->clear();
  Walker walker{ctx,
                objects,
                defaultMaterial,
                meshes,
                deformer,
                stats,
                scene,
                stepDeformers,
                instanceNodes,
                int(ctx.model.nodes.size()),
                instanceArrayMin};
  scene.environment = objects.environments[size_t(sceneIndex)];
  // Explicit stack of (node, parent's world matrix); children pushed in reverse so nodes are
  // visited in the order a recursive pre-order walk would (cameras keep the file's order).
  std::vector<std::pair<int, Mat4>> stack;
  const auto& roots = ctx.model.scenes[size_t(sceneIndex)].nodes;
  for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.push_back({*it, Mat4()});
  while (!stack.empty()) {
    auto [index, parentWorld] = stack.back();
    stack.pop_back();
    Mat4 world = parentWorld * objects.localMatrices[size_t(index)];
    walker.visit(index, world);
    const auto& children = ctx.model.nodes[size_t(index)].children;
    for (auto it = children.rbegin(); it != children.rend(); ++it) stack.push_back({*it, world});
  }
  if (walker.hiddenInstances)
    ctx.warn(std::to_string(walker.hiddenInstances) +
             " EXT_mesh_gpu_instancing instance(s) with a singular (zero-scale) transform were "
             "skipped");
  if (walker.hiddenNodes)
    ctx.warn(std::to_string(walker.hiddenNodes) +
             " node(s) with a singular (zero-scale) transform were skipped");
}

}  // namespace tray
