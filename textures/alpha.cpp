#include "textures/alpha.h"

#include <bit>
#include <cmath>

#include "textures/texture_sampler.h"

namespace tray {

namespace {

/// Texel index along one axis under a glTF wrap mode (glTF 2.0 §3.8.4.3).
int wrapTexel(int i, int n, TextureWrap wrap) {
  switch (wrap) {
    case TextureWrap::kClampToEdge:
      return std::clamp(i, 0, n - 1);
    case TextureWrap::kMirroredRepeat: {
      int period = 2 * n, k = ((i % period) + period) % period;
      return k < n ? k : period - 1 - k;
    }
    default:
      return ((i % n) + n) % n;
  }
}

/// lowbias32 (Chris Wellons' hash prospector): a cheap integer mix with full avalanche.
uint32_t mix(uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

}  // namespace

float textureAlpha(const TextureImage& image, const TextureRef& ref, Vec2 uv) {
  if (!image.hasAlpha() || image.width <= 0 || image.height <= 0) return 1.0f;
  const Vec2 t = transformUv(ref, uv);
  // Texel centres at (i + 0.5) / width; row 0 at v = 0, as the colour lookup.
  const float x = t.x * float(image.width) - 0.5f, y = t.y * float(image.height) - 0.5f;
  if (!std::isfinite(x) || !std::isfinite(y)) return 1.0f;
  const float fx = std::floor(x), fy = std::floor(y);
  // Far-away uvs: reduce first so the int conversion cannot overflow (wrap is periodic anyway
  // for repeat; clamp only needs the side).
  auto toInt = [](float f) { return int(std::clamp(f, -1e9f, 1e9f)); };
  const int x0 = toInt(fx), y0 = toInt(fy);
  const float wx = x - fx, wy = y - fy;
  auto at = [&](int i, int j) {
    const int u = wrapTexel(i, image.width, ref.wrapS), v = wrapTexel(j, image.height, ref.wrapT);
    return image.alphaAt(size_t(v) * size_t(image.width) + size_t(u));
  };
  if (ref.magFilter == TextureFilter::kNearest)
    return at(wx < 0.5f ? x0 : x0 + 1, wy < 0.5f ? y0 : y0 + 1);
  const float top = at(x0, y0) * (1 - wx) + at(x0 + 1, y0) * wx;
  const float bottom = at(x0, y0 + 1) * (1 - wx) + at(x0 + 1, y0 + 1) * wx;
  return top * (1 - wy) + bottom * wy;
}

Color vertexColor(const TriangleMesh& m, uint32_t tri, float b1, float b2) {
  if (m.colors.empty()) return Color(1.0f);
  const uint32_t* v = &m.indices[3 * size_t(tri)];
  return (1.0f - b1 - b2) * m.colors[v[0]] + b1 * m.colors[v[1]] + b2 * m.colors[v[2]];
}

float vertexAlpha(const TriangleMesh& m, uint32_t tri, float b1, float b2) {
  if (m.colorAlphas.empty()) return 1.0f;
  const uint32_t* v = &m.indices[3 * size_t(tri)];
  return (1.0f - b1 - b2) * m.colorAlphas[v[0]] + b1 * m.colorAlphas[v[1]] +
         b2 * m.colorAlphas[v[2]];
}

float meshAlpha(const Scene& scene, const TriangleMesh& mesh, uint32_t tri, float b1, float b2) {
  const Material& mat = scene.material(mesh.material);
  float a = mat.alpha * vertexAlpha(mesh, tri, b1, b2);
  const TextureRef& ref = mat.baseColorTexture;
  if (ref.valid() && size_t(ref.image) < scene.textures.size()) {
    const TextureImage& image = scene.textures[size_t(ref.image)];
    if (image.hasAlpha()) {
      const uint32_t* v = &mesh.indices[3 * size_t(tri)];
      const auto& uvs = ref.texCoord == 1 ? mesh.uvs1 : mesh.uvs;
      // No uv set: the barycentric fallback of Scene::surface.
      Vec2 uv{b1, b2};
      if (!uvs.empty()) {
        const float b0 = 1.0f - b1 - b2;
        uv = {b0 * uvs[v[0]].x + b1 * uvs[v[1]].x + b2 * uvs[v[2]].x,
              b0 * uvs[v[0]].y + b1 * uvs[v[1]].y + b2 * uvs[v[2]].y};
      }
      a *= textureAlpha(image, ref, uv);
    }
  }
  return std::clamp(a, 0.0f, 1.0f);
}

float coverage(const Scene& scene, const Hit& hit) {
  const Primitive& p = scene.primitives[hit.primitive];
  if (p.kind != Primitive::Kind::kMesh) return 1.0f;
  const TriangleMesh& mesh = scene.meshes[p.mesh];
  const Material& mat = scene.material(mesh.material);
  if (mat.alphaMode == AlphaMode::kOpaque) return 1.0f;
  const float a = meshAlpha(scene, mesh, hit.triangle, hit.b1, hit.b2);
  if (mat.alphaMode == AlphaMode::kMask) return a >= mat.alphaCutoff ? 1.0f : 0.0f;
  return a;
}

float alphaHash(const Ray& r, uint32_t primitive, uint32_t triangle) {
  uint32_t h = mix(primitive * 0x9e3779b9u + triangle);
  for (float f : {r.o.x, r.o.y, r.o.z, r.d.x, r.d.y, r.d.z})
    h = mix(h ^ std::bit_cast<uint32_t>(f));
  return float(h >> 8) * 0x1p-24f;
}

bool alphaAccepts(const Scene& scene, const Ray& worldRay, uint32_t primitive, uint32_t triangle,
                  float b1, float b2) {
  const TriangleMesh& mesh = scene.meshes[scene.primitives[primitive].mesh];
  const Material& mat = scene.material(mesh.material);
  if (mat.alphaMode == AlphaMode::kOpaque) return true;
  const float a = meshAlpha(scene, mesh, triangle, b1, b2);
  if (mat.alphaMode == AlphaMode::kMask) return a >= mat.alphaCutoff;
  if (worldRay.blend == BlendRays::kHit) return true;
  return alphaHash(worldRay, primitive, triangle) < a;
}

}  // namespace tray
