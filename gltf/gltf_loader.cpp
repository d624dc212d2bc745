#include "gltf/gltf_loader.h"

#include <malloc.h>

#include <algorithm>
#include <filesystem>
#include <new>

#include "gltf/gltf_animation.h"
#include "gltf/gltf_buffer_plan.h"
#include "gltf/gltf_cameras_lights.h"
#include "gltf/gltf_container.h"
#include "gltf/gltf_context.h"
#include "gltf/gltf_deform.h"
#include "gltf/gltf_environment.h"
#include "gltf/gltf_file_access.h"
#include "gltf/gltf_images.h"
#include "gltf/gltf_materials.h"
#include "gltf/gltf_meshes.h"
#include "gltf/gltf_motion.h"
#include "gltf/gltf_scene_graph.h"
#include "gltf/gltf_textures.h"
#include "gltf/gltf_unsupported.h"
#include "gltf/gltf_validate.h"
#include "gltf/gltf_variants.h"

// The loader in stages, each in its own file:
//   1. read the file (gltf_file_access) and check its envelope (gltf_container);
//   2. let tinygltf parse it, with file access routed through TRay's URI policy and images
//      left undecoded;
//   3. validate the whole document (gltf_validate, gltf_accessors), converting every camera,
//      light, node and environment once (convertObjects);
//   4. convert materials and meshes, then walk the chosen scene's nodes (gltf_scene_graph);
//   5. decode the images the materials use (gltf_images) and bind them (gltf_textures).

namespace tray {

namespace {

std::string firstLine(const std::string& text) {
  size_t start = text.find_first_not_of("\r\n ");
  if (start == std::string::npos) return "";
  return text.substr(start, text.find_first_of("\r\n", start) - start);
}

/// Parses a document's bytes; `policy` decides which URIs may be read. Images are decoded later
/// (OIIO, after validation): tinygltf only hands over their bytes.
tinygltf::Model parse(const std::vector<unsigned char>& bytes, const std::string& path,
                      const UriPolicy& policy, const LoadOptions& options, LoadReport* report,
                      ImageBytes& images, MemoryEstimate& memory) {
  if (bytes.empty()) failFile(path, "file is empty");
  if (bytes.size() > kMaxFileBytes) failFile(path, "file is larger than the 2 GiB limit");
  const bool binary = isGlb(bytes);
  std::string_view json =
      binary ? glbJson(path, bytes)
             : std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  checkJsonRoot(path, json);
  // Buffers before tinygltf reads them: the --max-memory check, and one read per file.
  const BufferPlan plan = planBuffers(json, policy);
  // A .glb gets the merged JSON only where that saves memory: rebuilding the container copies
  // its BIN chunk, which must be smaller than the duplicate reads it avoids.
  const size_t binBytes = binary ? bytes.size() - 20 - json.size() : 0;
  const bool merge = plan.merged > 0 && (!binary || plan.mergedBytes > binBytes);
  memory.buffers = plan.bytes + (merge ? 0 : plan.mergedBytes) + (merge && binary ? binBytes : 0);
  checkMemory(path, memory, options.maxMemoryBytes);
  std::vector<unsigned char> rebuilt;
  if (merge && binary) rebuilt = withGlbJson(bytes, plan.json);
  if (merge && !binary) json = plan.json;
  const std::vector<unsigned char>& document = rebuilt.empty() ? bytes : rebuilt;

  FileAccess access(policy);
  tinygltf::TinyGLTF gltf;
  gltf.SetFsCallbacks(access.callbacks());
  gltf.SetImageLoader(&ImageBytes::record, &images);
  tinygltf::Model model;
  std::string err, warn;
  // Sizes fit in unsigned int: files are capped at 2 GiB.
  bool ok = false;
  try {
    ok = binary ? gltf.LoadBinaryFromMemory(&model, &err, &warn, document.data(),
                                            unsigned(document.size()), policy.folder())
                : gltf.LoadASCIIFromString(&model, &err, &warn, json.data(), unsigned(json.size()),
                                           policy.folder());
  } catch (const std::bad_alloc&) {  // not a problem of the file: main reports it
    throw;
  } catch (const std::exception& e) {  // nlohmann type errors on oddly typed members
    failFile(path, std::string("tinygltf: ") + e.what());
  }
  // A refused or missing file is reported by tinygltf as "File not found" (or, for images,
  // only as a warning): TRay's own reason is more precise and is always an error.
  if (!access.firstProblem().empty()) failFile(path, access.firstProblem());
  if (!ok)
    failFile(path, firstLine(err).empty() ? "tinygltf could not parse the file" : firstLine(err));
  if (report) {
    for (size_t start = 0; start < warn.size();) {
      size_t end = std::min(warn.find('\n', start), warn.size());
      if (end > start)
        report->warnings.push_back(oneLine(path + ": " + warn.substr(start, end - start)));
      start = end + 1;
    }
  }
  return model;
}

int chooseScene(const GltfContext& ctx, int requested) {
  const int count = int(ctx.model.scenes.size());
  if (requested < -1) ctx.fail("scene index " + std::to_string(requested) + " is invalid");
  if (requested >= count)
    ctx.fail("scene " + std::to_string(requested) + " does not exist (the file has " +
             std::to_string(count) + ")");
  if (requested >= 0) return requested;
  if (ctx.model.defaultScene >= 0) return ctx.model.defaultScene;
  return count > 0 ? 0 : -1;  // a file without scenes is valid and renders nothing
}

void reportMeshStats(const GltfContext& ctx, const MeshStats& s) {
  if (s.pointAndLinePrimitives)
    ctx.warn("skipped " + std::to_string(s.pointAndLinePrimitives) +
             " point or line primitive(s): only triangles are rendered");
  if (s.primitivesWithoutPosition)
    ctx.warn("skipped " + std::to_string(s.primitivesWithoutPosition) +
             " primitive(s) without POSITION");
  if (s.degenerateTriangles)
    ctx.warn("dropped " + std::to_string(s.degenerateTriangles) + " degenerate triangle(s)");
  if (s.repairedAttributes)
    ctx.warn("replaced " + std::to_string(s.repairedAttributes) +
             " non-finite normal(s), tangent(s), texture coordinate(s) or colour(s) with zero");
}

/// The pose at options.time: animated nodes get new local matrices (the others keep theirs
/// exactly, so unanimated files render bit for bit as without a time). Empty without a time.
std::vector<NodePose> animate(const GltfContext& ctx, const LoadOptions& options,
                              const std::vector<Animation>& animations, int which,
                              ObjectTable& objects) {
  if (!options.time) return {};
  std::vector<NodePose> poses = poseAt(ctx, animations, which, *options.time);
  for (size_t i = 0; i < poses.size(); ++i)
    if (poses[i].animatesTransform())
      objects.localMatrices[i] = animatedMatrix(ctx, int(i), poses[i]);
  return poses;
}

Scene convert(const tinygltf::Model& model, const std::string& path, const LoadOptions& options,
              LoadReport* report, const ImageBytes& images, const UriPolicy& policy,
              MemoryEstimate& memory) {
  GltfContext ctx{model, path, report, options.ignoreRequiredExtensions};
  validateDocument(ctx);
  const std::vector<std::string> variants = readVariantNames(ctx);
  validateVariantMappings(ctx, variants.size());
  ctx.variant = chooseVariant(ctx, variants, options.variant);
  warnUnsupported(ctx);
  // Cameras, lights, nodes and environments converted once, placed or not.
  ObjectTable objects = convertObjects(ctx);
  const std::vector<Animation> animations = readAnimations(ctx);  // checked, used or not
  const int which = chooseAnimation(ctx, animations, options.animation);
  const std::vector<NodePose> poses = animate(ctx, options, animations, which, objects);
  const Deformer deformer(ctx, poses, worldMatrices(ctx, objects.localMatrices));
  const int sceneIndex = chooseScene(ctx, options.scene);

  Scene scene;
  scene.sourcePath = path;
  for (size_t i = 0; i < model.materials.size(); ++i)
    scene.materials.push_back(convertMaterial(ctx, int(i)));
  // Index of the glTF default material, appended below only if something uses it.
  const int defaultMaterial = int(model.materials.size());

  // Every mesh is converted (and so checked), used or not; the walk keeps the used ones.
  MeshTable meshes;
  MeshStats stats;
  for (size_t i = 0; i < model.meshes.size(); ++i)
    meshes.converted.push_back(convertMesh(ctx, int(i), defaultMaterial, stats));
  meshes.placed.resize(model.meshes.size());
  meshes.moved.assign(model.meshes.size(), false);
  reportMeshStats(ctx, stats);

  // Motion blur: skinned and morphed vertices posed at every step too.
  const MotionSteps steps{options.shutterOpen, options.shutterClose,
                          options.time ? options.motionSteps : 0};
  // Each step posed once: its deformer for the vertices, its world matrices for placements.
  std::vector<Deformer> stepDeformers;
  std::vector<std::vector<Mat4>> stepWorlds;
  for (float t : steps.count >= 2 ? steps.times() : std::vector<float>()) {
    PosedNodes posed = poseNodes(ctx, animations, which, objects.localMatrices, t);
    stepDeformers.emplace_back(ctx, posed.poses, posed.world);
    stepWorlds.push_back(std::move(posed.world));
  }
  // Per primitive: the node of an EXT_mesh_gpu_instancing instance, for motion (else -1).
  std::vector<int> instanceNodes;
  const bool moving = steps.count >= 2 || (options.time && options.previousTime);
  if (sceneIndex >= 0)
    addSceneNodes(ctx, objects, sceneIndex, defaultMaterial, meshes, deformer, stats, scene,
                  stepDeformers.empty() ? nullptr : &stepDeformers,
                  moving ? &instanceNodes : nullptr, options.instanceArrayMin);
  const std::vector<Mat4> frameWorld =
      moving ? worldMatrices(ctx, objects.localMatrices) : std::vector<Mat4>();
  if (steps.count >= 2)
    addMotionSteps(ctx, stepWorlds, deformer, steps, scene, instanceNodes, frameWorld);
  if (options.time && options.previousTime)
    addPreviousFrame(ctx, animations, which, objects.localMatrices, deformer, *options.previousTime,
                     scene, instanceNodes, frameWorld);
  if (deformer.renormalisedVertices())
    ctx.warn(std::to_string(deformer.renormalisedVertices()) +
             " skinned vertex(es) with weights not summing to 1: rescaled to 1");

  bool defaultUsed = false;
  for (const auto& m : scene.meshes) defaultUsed = defaultUsed || m.material == defaultMaterial;
  for (const auto& p : scene.primitives) defaultUsed = defaultUsed || p.material == defaultMaterial;
  if (defaultUsed) scene.materials.push_back(defaultGltfMaterial());
  if (!options.geometryOnly) {
    bindTextures(ctx, images, scene, memory, options.maxMemoryBytes);
    loadEnvironmentImage(ctx, images, policy, scene, options.maxMemoryBytes);
  }
  scene.textureCacheMB = options.textureCacheMB;
  if (report) report->memory = memory;
  scene.finalize();
  return scene;
}

}  // namespace

Scene loadGltf(const std::string& path, const LoadOptions& options, LoadReport* report) {
  Scene scene = GltfDocument(path, options, report).scene(options, report);
  // The document's buffers and the loader's temporaries are freed now; glibc keeps freed heap
  // pages resident (its mmap threshold grows after large frees), and the accelerator's build
  // would come on top of them: 10^6 instances, 12 MiB more peak (bench/instancing_bench).
  malloc_trim(0);
  return scene;
}

struct GltfDocument::Parsed {
  std::string path;
  UriPolicy policy;
  ImageBytes images;
  MemoryEstimate memory;
  tinygltf::Model model;
};

GltfDocument::GltfDocument(const std::string& path, const LoadOptions& options,
                           LoadReport* report) {
  std::vector<unsigned char> bytes;
  std::string problem;
  if (!readRegularFile(path, bytes, problem)) failFile(path, problem);
  const std::string folder = std::filesystem::path(path).parent_path().string();
  parsed_.reset(
      new Parsed{path, UriPolicy(folder.empty() ? "." : folder, options.allowAnyPath), {}, {}, {}});
  parsed_->model =
      parse(bytes, path, parsed_->policy, options, report, parsed_->images, parsed_->memory);
}

GltfDocument::~GltfDocument() = default;

Scene GltfDocument::scene(const LoadOptions& options, LoadReport* report) const {
  MemoryEstimate memory = parsed_->memory;  // each conversion counts its own textures
  return convert(parsed_->model, parsed_->path, options, report, parsed_->images, parsed_->policy,
                 memory);
}

std::optional<std::pair<float, float>> GltfDocument::animationRange(
    const LoadOptions& options) const {
  const GltfContext ctx{parsed_->model, parsed_->path, nullptr, options.ignoreRequiredExtensions};
  const std::vector<Animation> animations = readAnimations(ctx);
  if (animations.empty()) return std::nullopt;
  const int which = chooseAnimation(ctx, animations, options.animation);
  std::optional<std::pair<float, float>> range;
  for (size_t a = 0; a < animations.size(); ++a) {
    if (which >= 0 && size_t(which) != a) continue;
    for (const AnimationChannel& ch : animations[a].channels) {
      if (ch.keys.times.empty()) continue;
      const float first = ch.keys.times.front(), last = ch.keys.times.back();
      if (!range) range.emplace(first, last);
      range->first = std::min(range->first, first);
      range->second = std::max(range->second, last);
    }
  }
  return range;
}

Scene loadGltfFromMemory(const unsigned char* data, size_t size, const std::string& name,
                         const LoadOptions& options, LoadReport* report) {
  const std::vector<unsigned char> bytes(data, data + size);
  ImageBytes images;
  const UriPolicy policy = UriPolicy::noFiles();
  MemoryEstimate memory;
  tinygltf::Model model = parse(bytes, name, policy, options, report, images, memory);
  return convert(model, name, options, report, images, policy, memory);
}

}  // namespace tray
