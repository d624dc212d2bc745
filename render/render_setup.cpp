#include "render/render_setup.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <system_error>
#include <vector>

#include "core/error.h"

namespace tray {

namespace {

/// "0 \"Front\" (node \"FrontCam\"), 1 ..." for the error message.
std::string cameraList(const Scene& scene) {
  if (scene.cameras.empty()) return "the scene places no camera";
  std::string list = "the scene places:";
  for (size_t i = 0; i < scene.cameras.size(); ++i) {
    const CameraDesc& c = scene.cameras[i];
    list += (i ? ", " : " ") + std::to_string(c.gltfIndex >= 0 ? c.gltfIndex : int(i));
    // A camera without a name of its own carries its node's (gltf_scene_graph.cpp).
    if (!c.name.empty() && c.name != c.nodeName) list += " \"" + c.name + "\"";
    if (!c.nodeName.empty()) list += " (node \"" + c.nodeName + "\")";
  }
  return list;
}

bool allDigits(const std::string& s) {
  return !s.empty() && s.size() < 10 && s.find_first_not_of("0123456789") == std::string::npos;
}

}  // namespace

int findCamera(const Scene& scene, const std::string& which) {
  const auto& cams = scene.cameras;
  if (which.empty()) {
    if (cams.empty()) return -1;
    int best = 0;
    for (size_t i = 1; i < cams.size(); ++i)
      if (cams[i].gltfIndex >= 0 &&
          (cams[size_t(best)].gltfIndex < 0 || cams[i].gltfIndex < cams[size_t(best)].gltfIndex))
        best = int(i);
    return best;
  }
  if (allDigits(which)) {
    const int n = std::stoi(which);
    for (size_t i = 0; i < cams.size(); ++i)
      if (cams[i].gltfIndex == n || (cams[i].gltfIndex < 0 && size_t(n) == i)) return int(i);
    throw Error(scene.sourcePath + ": --camera " + which + ": no such camera; " +
                cameraList(scene));
  }
  for (size_t i = 0; i < cams.size(); ++i)
    if (cams[i].nodeName == which || cams[i].name == which) return int(i);
  throw Error(scene.sourcePath + ": --camera '" + which +
              "': no camera or camera node has "
              "that name; " +
              cameraList(scene));
}

CameraDesc chooseCamera(const Scene& scene, const std::string& which) {
  const int i = findCamera(scene, which);
  if (i >= 0) return scene.cameras[size_t(i)];
  return Camera::framing(scene.bounds(), 4.0f / 3.0f);
}

CameraDesc chooseCamera(const Scene& scene, int index) {
  return chooseCamera(scene, index < 0 ? std::string() : std::to_string(index));
}

void applyLensOptions(CameraDesc& camera, const RenderSettings& settings) {
  if (settings.isSet("lens-radius")) camera.lensRadius = settings.getFloat("lens-radius");
  if (settings.isSet("focus-distance")) camera.focusDistance = settings.getFloat("focus-distance");
  if (settings.isSet("aperture-blades")) {
    const int blades = settings.getInt("aperture-blades");
    if (blades == 1 || blades == 2)
      throw Error("--aperture-blades " + std::to_string(blades) + ": expected 0 (round) or 3..64");
    camera.apertureBlades = blades;
  }
  if (camera.lensRadius > 0 && !(camera.focusDistance > 0))
    throw Error("--lens-radius " + formatOptionValue(camera.lensRadius) +
                " needs --focus-distance > 0 (or TRAY_camera focusDistance on the camera)");
}

namespace {

/// Mean linear RGB of a decoded texture (1 when the reference is invalid or the image empty).
Color meanOf(const Scene& scene, const TextureRef& ref) {
  if (!ref.valid() || size_t(ref.image) >= scene.textures.size()) return Color(1.0f);
  const TextureImage& im = scene.textures[size_t(ref.image)];
  if (!im.valid()) return Color(1.0f);
  const size_t n = size_t(im.width) * size_t(im.height);
  double sum[3] = {0, 0, 0};
  std::vector<float> row(size_t(im.width) * 3);
  for (int y = 0; y < im.height; ++y) {  // row by row: the texels may be compact codes
    im.row(y, row.data());
    for (size_t x = 0; x < size_t(im.width); ++x)
      for (int c = 0; c < 3; ++c) sum[c] += row[3 * x + size_t(c)];
  }
  return Color(float(sum[0] / n), float(sum[1] / n), float(sum[2] / n));
}

/// glTF 2.0's core emission is emissiveFactor (each in [0, 1]) x an 8-bit texture: radiance
/// at most 1, what assets use for labels, screens and LEDs that glow in any light. Only
/// KHR_materials_emissive_strength (or TRay's own extensions) can say more, as a light needs.
bool brighterThanCoreGltf(const Material& m) {
  return maxComponent(m.emissive) > 1.0f;
}

/// Adds the world area of mesh's triangles placed by toWorld (non-finite ones left out), and
/// `power` per unit of it.
void addPlacedArea(const TriangleMesh& mesh, const Transform& toWorld, double power,
                   EmissionSummary& e) {
  for (size_t t = 0; t < mesh.triangleCount(); ++t) {
    const uint32_t* idx = &mesh.indices[3 * t];
    const Vec3 a = toWorld.point(mesh.positions[idx[0]]);
    const float area = 0.5f * length(cross(toWorld.point(mesh.positions[idx[1]]) - a,
                                           toWorld.point(mesh.positions[idx[2]]) - a));
    if (!std::isfinite(area)) continue;
    e.surfaceArea += area;
    e.meshPower += double(area) * power;
  }
}

}  // namespace

EmissionSummary summarizeEmission(const Scene& scene) {
  EmissionSummary e;
  std::vector<float> exitance(scene.materials.size(), -1.0f);  // per material, lazily
  for (const Primitive& prim : scene.primitives) {
    const int mi =
        prim.kind == Primitive::Kind::kMesh ? scene.meshes[prim.mesh].material : prim.material;
    const Material& m = scene.material(mi);
    float& M = exitance[size_t(mi)];
    if (M < 0) {  // radiant exitance pi L of a Lambertian emitter, L = factor x mean texel
      const Color L = m.emissive * meanOf(scene, m.emissiveTexture);
      M = isFinite(L) ? kPi * luminance(L) * (m.doubleSided ? 2.0f : 1.0f) : 0.0f;
    }
    if (prim.kind == Primitive::Kind::kShape) {
      // No area for analytic shapes here: any emissive one counts as a light.
      if (M > 0) e.emissiveShapes = true;
      continue;
    }
    // Meshes of core glTF glow (radiance <= 1) add area, not power. Decided here, not in the
    // cache: a shape may share the material, and any emissive shape counts.
    // Instance arrays (never emissive, Scene::finalize) add area only: below.
    if (prim.instances) continue;
    const double power = brighterThanCoreGltf(m) ? double(M) : 0.0;
    addPlacedArea(scene.meshes[prim.mesh], prim.toWorld, power, e);
  }
  // Their area only matters against some emitted power: 10^6 instances of a 10^3-triangle mesh
  // are 10^9 triangles to place, spent only then.
  if (e.meshPower > 0 && !e.emissiveShapes)
    for (uint32_t i = 0; i < scene.primitives.size(); ++i)
      for (uint32_t k = 0; scene.primitives[i].instances && k < scene.primitives[i].instanceCount();
           ++k) {
        Transform scratch;
        addPlacedArea(scene.meshes[scene.primitives[i].mesh], scene.placement(i, k, scratch), 0.0,
                      e);
      }
  return e;
}

bool EmissionSummary::meaningful() const {
  if (emissiveShapes) return true;
  return meshPower > 0 && meshPower >= kMeaningfulShare * kDefaultIrradiance * surfaceArea / 4;
}

bool addDefaultLightingIfUnlit(Scene& scene, const CameraDesc& camera) {
  if (!scene.lights.empty() || !isBlack(scene.environment.ambient) ||
      !isBlack(scene.environment.background) || scene.environment.map)
    return false;
  if (summarizeEmission(scene).meaningful()) return false;
  // glTF cameras look down -Z with +Y up; the key light travels forward, down and right.
  const Vec3 forward = normalize(camera.toWorld.vector(Vec3(0, 0, -1)));
  const Vec3 up = normalize(camera.toWorld.vector(Vec3(0, 1, 0)));
  const Vec3 right = normalize(cross(forward, up));
  PunctualLightDesc key;
  key.type = PunctualLightDesc::Type::kDirectional;
  key.intensity = Color(EmissionSummary::kDefaultIrradiance);
  key.direction = normalize(forward - 0.6f * up + 0.4f * right);
  scene.lights.push_back(key);
  scene.environment.ambient = Color(0.1f);
  scene.environment.background = Color(0.1f);
  return true;
}

namespace {

const Vec3 kAxes[] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};

/// The material a hit shows (a CSG hit's own, else its primitive's or mesh's).
const Material& hitMaterial(const Scene& scene, const Hit& hit) {
  if (hit.material >= 0) return scene.material(hit.material);
  const Primitive& p = scene.primitives[hit.primitive];
  return scene.material(p.kind == Primitive::Kind::kMesh ? scene.meshes[p.mesh].material
                                                         : p.material);
}

}  // namespace

bool cameraEnclosed(const CameraDesc& camera, const Accelerator& accel) {
  const Vec3 eye = camera.toWorld.point(Vec3(0.0f));
  for (const Vec3& d : kAxes) {
    Hit hit;
    if (!accel.intersect(Ray{eye, d}, hit)) return false;
  }
  return true;
}

bool useHeadlightIfEnclosed(Scene& scene, const CameraDesc& camera, const Accelerator& accel) {
  if (scene.lights.empty() || scene.lights.back().type != PunctualLightDesc::Type::kDirectional)
    return false;
  const Vec3 eye = camera.toWorld.point(Vec3(0.0f));
  Hit towardsLight;  // light gets in (or out) that way, or along an axis
  if (!accel.intersect(Ray{eye, -scene.lights.back().direction}, towardsLight) ||
      !cameraEnclosed(camera, accel))
    return false;
  // The subject's distance: where the centre of the view meets the scene.
  Hit centre;
  const Vec3 forward = normalize(camera.toWorld.vector(Vec3(0, 0, -1)));
  const float d = accel.intersect(Ray{eye, forward}, centre) ? centre.t : 1.0f;
  PunctualLightDesc headlight;
  headlight.type = PunctualLightDesc::Type::kPoint;
  headlight.position = eye;
  headlight.intensity = Color(EmissionSummary::kDefaultIrradiance * d * d);
  scene.lights.back() = headlight;
  return true;
}

bool useUnlitEnclosureAsLight(Scene& scene, const CameraDesc& camera, const Accelerator& accel) {
  if (scene.lights.empty() || scene.lights.back().type != PunctualLightDesc::Type::kDirectional)
    return false;
  const Vec3 eye = camera.toWorld.point(Vec3(0.0f));
  std::vector<Vec3> directions(std::begin(kAxes), std::end(kAxes));
  directions.push_back(-scene.lights.back().direction);
  for (const Vec3& d : directions) {
    // Through what stands in the way (the asset itself), to what lies behind everything.
    Ray ray{eye, d};
    Hit hit;
    const Material* last = nullptr;
    for (int crossed = 0; crossed < 16 && accel.intersect(ray, hit); ++crossed) {
      last = &hitMaterial(scene, hit);
      if (last->unlit) break;
      ray.tmin = hit.t * (1.0f + 1e-4f) + 1e-4f;
      hit = Hit{};
    }
    // Escaped, or ended on a lit surface: no sky that way. A black unlit surface stands for
    // none either (a texture counts as colour).
    if (!last || !last->unlit ||
        (maxComponent(last->baseColor) <= 0.0f && !last->baseColorTexture.valid()))
      return false;
  }
  scene.lights.pop_back();  // the default key light, and the default 0.1 environment
  scene.environment.ambient = Color(0.0f);
  scene.environment.background = Color(0.0f);
  return true;
}

ImageSize resolveImageSize(const std::string& text, const CameraDesc& camera) {
  ImageSize s;
  if (text.empty()) {
    float aspect = camera.aspectRatio > 0 ? camera.aspectRatio : 4.0f / 3.0f;
    // An orthographic camera's extents are its aspect (glTF 2.0 §3.10.3: xmag / ymag): a
    // square view renders square, not at 4:3 with the sides widened.
    if (camera.type == CameraDesc::Type::kOrthographic && !(camera.aspectRatio > 0) &&
        camera.xmag > 0 && camera.ymag > 0 && std::isfinite(camera.xmag / camera.ymag))
      aspect = std::clamp(camera.xmag / camera.ymag, 1.0f / 16384, 16384.0f);
    s.height = std::max(1, int(std::lround(s.width / aspect)));
    return s;
  }
  // Digits only, each side parsed whole (std::from_chars refuses what does not fit: no
  // wrap-around, as sscanf's %d gave 4294967360x48 -> 64x48).
  const auto side = [&](const char* first, const char* last, int& out) {
    if (first == last || *first < '0' || *first > '9') return false;
    int64_t v = 0;
    const auto [end, ec] = std::from_chars(first, last, v);
    if (ec != std::errc() || end != last || v < 1 || v > 16384) return false;
    out = int(v);
    return true;
  };
  const size_t x = text.find('x');
  const char* begin = text.data();
  if (x == std::string::npos || !side(begin, begin + x, s.width) ||
      !side(begin + x + 1, begin + text.size(), s.height))
    throw Error("--resolution '" + text + "': expected WxH with 1..16384 pixels per side");
  return s;
}

}  // namespace tray
