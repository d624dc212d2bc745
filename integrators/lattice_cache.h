#pragma once
// The adaptive integrator's lattice samples, kept while a pixel may still read them (issue 40:
// one cache of every point of the image took 2.79 GB for a textured asset at 960 x 720). The
// lattice is cut into bands of kBandRows pixel rows; a pixel reads points of its own band and
// of the ones beside it (its corners, and --aa-robust's look at the 8 x 8 tiles around), so a
// band is dropped once it and both neighbours have every pixel done. A point is traced once
// while its band is kept; what is dropped is never read again in a render of the whole image
// (and were it read, it would be traced again to the same value: a point's sample depends on
// its coordinates alone).
#include <tbb/concurrent_hash_map.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <shared_mutex>

namespace tray {

template <class Sample>
class LatticeCache {
 public:
  /// Pixel rows per band: a pixel's reads reach at most 16 rows beyond its own (--aa-robust's
  /// neighbouring 8 x 8 tiles), so within the bands beside its own.
  static constexpr int kBandRows = 16;

  /// An image of width x height pixels, `scale` lattice cells per pixel side.
  LatticeCache(int width, int height, uint32_t scale)
      : width_(width),
        height_(height),
        scale_(scale),
        latticeWidth_(uint64_t(width) * scale + 1),
        bandCount_((height + kBandRows - 1) / kBandRows),
        bands_(std::make_unique<Band[]>(size_t(std::max(bandCount_, 1)))) {}

  /// Lattice point (i, j): traced by trace() on first use while its band is kept. The write
  /// accessor locks the entry while it is traced, so a second thread asking for it waits
  /// instead of tracing it again.
  template <class Trace>
  Sample get(uint32_t i, uint32_t j, Trace trace) {
    Band& band = bands_[size_t(bandOf(j))];
    std::shared_lock lock(band.mutex);
    const uint64_t k = key(i, j);
    {
      typename Map::const_accessor found;
      if (band.points.find(found, k)) return found->second;
    }
    typename Map::accessor acc;
    if (band.points.insert(acc, k)) {
      acc->second = trace();
      traced_.fetch_add(1, std::memory_order_relaxed);
      const uint64_t live = live_.fetch_add(1, std::memory_order_relaxed) + 1;
      uint64_t peak = peak_.load(std::memory_order_relaxed);
      while (live > peak && !peak_.compare_exchange_weak(peak, live, std::memory_order_relaxed)) {
      }
    }
    return acc->second;
  }

  /// Point (i, j)'s number: distinct for every point of the lattice.
  uint64_t key(uint32_t i, uint32_t j) const { return uint64_t(j) * latticeWidth_ + i; }

  /// Pixel row y's pixel is finished (once per pixel): bands no pixel will read again go.
  void pixelDone(int y) {
    const int b = y / kBandRows;
    if (bands_[size_t(b)].pixelsDone.fetch_add(1, std::memory_order_acq_rel) + 1 !=
        pixelsIn(b))
      return;
    for (int k = b - 1; k <= b + 1; ++k)
      if (done(k - 1) && done(k) && done(k + 1)) drop(k);
  }

  /// Points traced so far (a point dropped and traced again counts twice), and the most kept at
  /// once.
  uint64_t traced() const { return traced_.load(); }
  uint64_t peakKept() const { return peak_.load(); }

 private:
  using Map = tbb::concurrent_hash_map<uint64_t, Sample>;
  struct Band {
    std::shared_mutex mutex;  ///< shared: lookups and traces; exclusive: dropping the band
    Map points;
    std::atomic<int> pixelsDone{0};
    bool dropped = false;  ///< under the exclusive lock
  };

  int bandOf(uint32_t j) const {
    return std::min(int(j / (scale_ * uint32_t(kBandRows))), std::max(bandCount_ - 1, 0));
  }
  int pixelsIn(int b) const { return width_ * std::min(kBandRows, height_ - b * kBandRows); }
  /// Band b has every pixel done (bands beyond the image count as done).
  bool done(int b) const {
    return b < 0 || b >= bandCount_ ||
           bands_[size_t(b)].pixelsDone.load(std::memory_order_acquire) == pixelsIn(b);
  }
  void drop(int b) {
    if (b < 0 || b >= bandCount_) return;
    Band& band = bands_[size_t(b)];
    std::unique_lock lock(band.mutex);
    if (band.dropped) return;
    band.dropped = true;
    live_.fetch_sub(band.points.size(), std::memory_order_relaxed);
    band.points.clear();
  }

  int width_, height_;
  uint32_t scale_;
  uint64_t latticeWidth_;
  int bandCount_;
  std::unique_ptr<Band[]> bands_;
  std::atomic<uint64_t> traced_{0}, live_{0}, peak_{0};
};

}  // namespace tray
