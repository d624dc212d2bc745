#pragma once
// Room for an object that a hot function builds only on some paths, without the zero-fill that
// GCC 12 emits for std::optional's storage at its declaration and for arrays of structs whose
// members all default to zero (a `rep stos`, microcoded, slow to start: objdump of
// PathEstimator::step and MaterialEvaluator::modulate, docs/wavefront.md).
#include <type_traits>

namespace tray {

/// `value` is not constructed: the owner builds it by placement new (or assigns a trivially
/// copyable T) before reading it, and nothing is destroyed.
template <class T>
union Unbuilt {
  static_assert(std::is_trivially_destructible_v<T>);
  Unbuilt() {}  // NOLINT(modernize-use-equals-default): deliberately unbuilt
  T value;
};

}  // namespace tray
