#pragma once
#include "core/material.h"
#include "materials/dispersion.h"

namespace tray {

/// The refractive media a path is inside, for nested dielectrics (glass filled with water, a
/// bubble in glass). Schmidt & Budge 2002, "Simple Nested Dielectrics in Ray Traced Images":
/// the medium in effect is the entered one of highest Material::priority (ties: the most
/// recently entered); crossing the surface of a medium that is not in effect on either side is
/// a "false" interface, which the path passes straight through. A fixed array: no allocation.
class MediumStack {
 public:
  static constexpr int kCapacity = 8;
  /// What happens where a path meets the surface of transmissive material `id`.
  struct Interface {
    bool real = true;          ///< false: pass through without scattering
    float etaI = 1, etaT = 1;  ///< IOR on the arriving side and on the far side
  };

  /// `entering`: the path arrives from the surface's outside (SurfacePoint::frontFace).
  Interface interface(int id, const Material& m, bool entering) const {
    Interface r;
    int cur = current();
    if (entering) {
      r.real = cur < 0 || entries_[cur].priority <= m.priority;
      r.etaI = cur < 0 ? 1.0f : entries_[cur].ior;
      r.etaT = iorOf(m);
      return r;
    }
    int at = find(id);
    if (at < 0) {  // leaving a medium never entered (the path started inside it)
      r.etaI = iorOf(m);
      r.etaT = cur < 0 ? 1.0f : entries_[cur].ior;
      return r;
    }
    r.real = at == cur;
    r.etaI = iorOf(m);
    int next = current(at);
    r.etaT = next < 0 ? 1.0f : entries_[next].ior;
    return r;
  }
  /// Records that the path went through `id`'s surface.
  void cross(int id, const Material& m, bool entering) {
    if (entering) {
      if (size_ < kCapacity)
        entries_[size_++] = {id,
                             m.priority,
                             iorOf(m),
                             m.layers.absorption(),
                             m.layers.scatteringMedium,
                             m.layers.scattering,
                             m.layers.scatterAnisotropy};
      return;
    }
    int at = find(id);
    if (at < 0) return;
    for (int i = at; i + 1 < size_; ++i) entries_[i] = entries_[i + 1];
    --size_;
  }
  /// IOR of the medium in effect (1 outside everything).
  float currentIor() const {
    int c = current();
    return c < 0 ? 1.0f : entries_[c].ior;
  }
  /// Absorption coefficient sigma_a of the medium in effect (KHR_materials_volume; 0 outside
  /// everything): the one that fills the space the path is crossing.
  Color currentAbsorption() const {
    int c = current();
    return c < 0 ? Color(0.0f) : entries_[c].sigmaA;
  }
  /// The scattering medium in effect (TRAY_materials_scattering, docs/subsurface.md): true
  /// with its sigma_a, sigma_s and Henyey-Greenstein g; false outside every medium or in one
  /// that only absorbs.
  bool currentScattering(Color& sigmaA, Color& sigmaS, float& g) const {
    int c = current();
    if (c < 0 || !entries_[c].scatters) return false;
    sigmaA = entries_[c].sigmaA, sigmaS = entries_[c].sigmaS, g = entries_[c].g;
    return true;
  }
  /// Whether the medium in effect scatters (cheap: no medium, no search).
  bool scatters() const {
    if (size_ == 0) return false;
    int c = current();
    return entries_[c].scatters;
  }
  /// Extinction sigma_t = sigma_a + sigma_s of the medium in effect: what an unscattered
  /// (shadow) segment through it is attenuated by. sigma_a alone in a medium that does not
  /// scatter.
  Color currentExtinction() const {
    int c = current();
    if (c < 0) return Color(0.0f);
    return entries_[c].scatters ? entries_[c].sigmaA + entries_[c].sigmaS : entries_[c].sigmaA;
  }
  int size() const { return size_; }
  /// KHR_materials_dispersion: the one wavelength (nm) the path carries since it first met
  /// dispersive glass (hero-wavelength style, docs/materials-iridescence-dispersion.md); 0: none
  /// chosen, and every IOR is the material's own.
  float wavelength() const { return wavelength_; }
  void setWavelength(float nm) { wavelength_ = nm; }
  /// A material's IOR for this path: n(lambda) for dispersive glass once a wavelength is chosen.
  float iorOf(const Material& m) const {
    if (wavelength_ > 0 && m.layers.dispersion > 0)
      return dispersiveIor(m.ior, m.layers.dispersion, wavelength_);
    return m.ior;
  }

 private:
  struct Entry {
    int id = -1;
    int priority = 0;
    float ior = 1;
    Color sigmaA{0.0f};
    bool scatters = false;  ///< TRAY_materials_scattering: sigmaS and g below apply
    Color sigmaS{0.0f};
    float g = 0;
  };
  /// Index of the medium in effect, ignoring entry `skip`; -1 if none.
  int current(int skip = -1) const {
    int best = -1;
    for (int i = 0; i < size_; ++i)
      if (i != skip && (best < 0 || entries_[i].priority >= entries_[best].priority)) best = i;
    return best;
  }
  int find(int id) const {
    for (int i = size_ - 1; i >= 0; --i)
      if (entries_[i].id == id) return i;
    return -1;
  }
  /// First: a path outside every medium reads only this (one cache line of the path's state,
  /// the entries after it untouched).
  int size_ = 0;
  float wavelength_ = 0;  ///< nm; 0: no wavelength chosen (see wavelength())
  /// Only the first size_ entries are ever read: the rest are left unbuilt. Every path state
  /// holds a stack, made per camera ray; building all eight entries cost about 40
  /// instructions per path (callgrind, heavy spheres).
  union Entries {
    Entry at[kCapacity];
    Entries() {}  // NOLINT: deliberately unbuilt
    Entry& operator[](int i) { return at[i]; }
    const Entry& operator[](int i) const { return at[i]; }
  } entries_;
};

}  // namespace tray
