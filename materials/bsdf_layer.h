#pragma once
// Layers over the glTF base BSDF (KHR_materials_clearcoat, KHR_materials_sheen, ...): each one
// a class in a file of its own, registered by one line in materials/bsdf_layers.h. Every layer
// has the form the glTF extensions give their layering (albedo scaling, Conty Estevez & Kulla
// 2017; KHR_materials_clearcoat and KHR_materials_sheen READMEs):
//   f(wo, wi) = f_layer(wo, wi) + baseScale(wo, wi) f_below(wo, wi)
// where f_below is the next layer down, and under the last the base mixture (metal, glass,
// plastic). Bsdf samples the layer with the layer's probability at wo, else what lies below,
// and evaluates the whole stack for a continuous sample (docs/materials.md, "Layers").
//
// A layer L provides (world-space directions; `base` is the base's shading frame):
//   static bool applies(const ShadingMaterial& m);   the material has this layer
//   L(const ShadingMaterial& m, const Frame& base);    built per shading point, on the stack
//   bool isDelta() const;                              its own lobe is a delta (a mirror)
//   L::At at(const Vec3& wo) const;                    what wo decides, with a `probability`
//                                                      of sampling the layer's own lobe
//   Color eval(const Vec3& wo, const Vec3& wi, float& pdf, uint8_t kinds) const;
//                                                      its own f (of the LobeKinds in kinds)
//                                                      and its own pdf
//   float baseScale(const L::At& at, const Vec3& wi) const;
//   BsdfSample sample(const Vec3& wo, Vec2 u) const;   its own lobe's sample; a delta sample's
//                                                      f is its coefficient in f_layer above
// L must be trivially destructible (Bsdf holds it unbuilt until a material asks for it).
#include <cstddef>
#include <cstdint>
#include <new>
#include <tuple>
#include <utility>

#include "core/sampling.h"
#include "core/unbuilt.h"
#include "core/material.h"

namespace tray {

/// The kinds of lobe an evaluation includes (Bsdf::evalLobes splits the value by kind).
enum LobeKinds : uint8_t {
  kDiffuseLobes = 1,
  kSpecularLobes = 2,
  kTransmissionLobes = 4,
  kAllLobes = kDiffuseLobes | kSpecularLobes | kTransmissionLobes,
};

/// The layers a material may have, outermost first, each built only where it applies.
template <class... Layers>
class LayerStack {
 public:
  static constexpr size_t kCount = sizeof...(Layers);
  static_assert(kCount <= 8, "one bit per layer in on_");
  template <size_t I>
  using Layer = std::tuple_element_t<I, std::tuple<Layers...>>;

  /// Some layer applies to m: not the base mixture alone.
  static bool anyApplies(const ShadingMaterial& m) { return (Layers::applies(m) || ...); }
  /// Builds the layers that apply to m.
  void init(const ShadingMaterial& m, const Frame& base) {
    initEach(m, base, std::index_sequence_for<Layers...>{});
  }
  bool any() const { return on_ != 0; }
  template <size_t I>
  bool on() const {
    return (on_ >> I) & 1u;
  }
  template <size_t I>
  const Layer<I>& get() const {
    return std::get<I>(slots_).value;
  }
  /// Some layer has a lobe that is not a delta: light sampling helps.
  bool anyNonDelta() const { return anyNonDelta(std::index_sequence_for<Layers...>{}); }

 private:
  template <size_t... I>
  void initEach(const ShadingMaterial& m, const Frame& base, std::index_sequence<I...>) {
    (
        [&] {
          if (!Layer<I>::applies(m)) return;
          new (&std::get<I>(slots_).value) Layer<I>(m, base);
          on_ = uint8_t(on_ | (1u << I));
        }(),
        ...);
  }
  template <size_t... I>
  bool anyNonDelta(std::index_sequence<I...>) const {
    return ((on<I>() && !get<I>().isDelta()) || ...);
  }
  std::tuple<Unbuilt<Layers>...> slots_;
  uint8_t on_ = 0;
};

}  // namespace tray
