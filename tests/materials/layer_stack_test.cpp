// The layer registry of Bsdf (materials/bsdf_layer.h, bsdf_layers.h): LayerStack builds exactly
// the layers a material has, outermost first, and says whether any has a lobe light sampling
// helps; the registered list is what the SIMD stages' tests and Bsdf's own read.
#include "materials/bsdf_layer.h"

#include <gtest/gtest.h>

#include <type_traits>

#include "materials/bsdf.h"
#include "materials/bsdf_layers.h"
#include "tests/scene_builder.h"

// GCC 12 reads the toy's `delta` of an unbuilt slot speculatively in anyNonDelta's
// `on<I>() && !get<I>().isDelta()` (branchless, inlined) and warns; the value is never used
// there unless the layer was built.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

namespace tray {
namespace {

/// A toy layer: applies where metallic is exactly 0.25, a delta where roughness is 0; counts
/// how many were built.
int built = 0;
struct ToyLayer {
  static bool applies(const ShadingMaterial& m) { return m.metallic == 0.25f; }
  ToyLayer(const ShadingMaterial& m, const Frame& base) : delta(m.roughness == 0), n(base.n) {
    ++built;
  }
  bool isDelta() const { return delta; }
  bool delta;
  Vec3 n;
};
struct OtherToyLayer {
  static bool applies(const ShadingMaterial& m) { return m.transmission == 0.5f; }
  OtherToyLayer(const ShadingMaterial&, const Frame&) { ++built; }
  bool isDelta() const { return false; }
};
using ToyStack = LayerStack<ToyLayer, OtherToyLayer>;

ShadingMaterial material(float metallic, float roughness, float transmission) {
  ShadingMaterial m = ShadingMaterial::of(test::diffuse(Color(0.5f)), Vec3(0, 0, 1));
  m.metallic = metallic, m.roughness = roughness, m.transmission = transmission;
  return m;
}

TEST(LayerStack, BuildsOnlyTheLayersThatApply) {
  const Frame frame = Frame::fromNormal(Vec3(0, 1, 0));
  built = 0;
  ToyStack none;
  none.init(material(0.0f, 0.5f, 0.0f), frame);
  EXPECT_EQ(built, 0);
  EXPECT_FALSE(none.any());
  EXPECT_FALSE(none.anyNonDelta());
  EXPECT_FALSE(ToyStack::anyApplies(material(0.0f, 0.5f, 0.0f)));

  ToyStack first;
  first.init(material(0.25f, 0.0f, 0.0f), frame);
  EXPECT_EQ(built, 1);
  EXPECT_TRUE(first.any());
  EXPECT_TRUE(first.on<0>());
  EXPECT_FALSE(first.on<1>());
  EXPECT_EQ(first.get<0>().n, Vec3(0, 1, 0));  // built with the base's frame
  EXPECT_FALSE(first.anyNonDelta());           // its one lobe is a delta

  ToyStack both;
  both.init(material(0.25f, 0.0f, 0.5f), frame);
  EXPECT_EQ(built, 3);
  EXPECT_TRUE(both.on<0>() && both.on<1>());
  EXPECT_TRUE(both.anyNonDelta());
  EXPECT_TRUE(ToyStack::anyApplies(material(0.0f, 0.5f, 0.5f)));
}

TEST(BsdfLayers, ClearcoatOverSheenAsRegistered) {
  ShadingMaterial m = material(0.0f, 0.5f, 0.0f);
  EXPECT_FALSE(BsdfLayers::anyApplies(m));
  m.clearcoat = 0.5f;
  EXPECT_TRUE(BsdfLayers::anyApplies(m));
  EXPECT_TRUE(ClearcoatLayer::applies(m));
  m.clearcoat = 0.0f, m.sheenColor = Color(0.3f);
  EXPECT_TRUE(SheenLayer::applies(m));
  EXPECT_TRUE((std::is_same_v<BsdfLayers::Layer<0>, ClearcoatLayer>));  // outermost
  EXPECT_TRUE((std::is_same_v<BsdfLayers::Layer<1>, SheenLayer>));
  // A layer takes a material out of the SIMD stages' lists.
  EXPECT_FALSE(Bsdf::isGgxMixture(m));
  EXPECT_FALSE(Bsdf::isLambertOnly(m));
  // A mirror coat over a mirror base: every lobe a delta, no light sample.
  ShadingMaterial mirror = material(1.0f, 0.0f, 0.0f);
  mirror.clearcoat = 1.0f, mirror.clearcoatRoughness = 0.0f;
  EXPECT_FALSE(Bsdf(mirror, Vec3(0, 0, 1), 1.5f).hasNonDelta());
  mirror.clearcoatRoughness = 0.5f;
  EXPECT_TRUE(Bsdf(mirror, Vec3(0, 0, 1), 1.5f).hasNonDelta());
}

}  // namespace
}  // namespace tray
