#pragma once
// The film cut into square tiles of RenderOptions::tileSize, row by row: the work units the
// tile renderer (render/renderer.cpp) and the pass renderer (render/pass_renderer.cpp) hand to
// TBB. Only work units: no pixel depends on them.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>

namespace tray {

class TileGrid {
 public:
  /// Film pixels [x0, x1) x [y0, y1).
  struct Tile {
    int x0, y0, x1, y1;
  };
  TileGrid(int width, int height, int tileSize)
      : width_(width),
        height_(height),
        size_(std::max(1, tileSize)),
        across_((width + size_ - 1) / size_),
        count_(across_ * ((height + size_ - 1) / size_)) {}
  int count() const { return count_; }
  Tile at(int tile) const {
    const int x0 = (tile % across_) * size_, y0 = (tile / across_) * size_;
    return {x0, y0, std::min(x0 + size_, width_), std::min(y0 + size_, height_)};
  }
  /// Runs fn(tile index) for every tile in parallel, in the caller's task arena.
  template <class Fn>
  void forEach(Fn&& fn) const {
    tbb::parallel_for(tbb::blocked_range<int>(0, count_, 1), [&](const tbb::blocked_range<int>& r) {
      for (int t = r.begin(); t != r.end(); ++t) fn(t);
    });
  }

 private:
  int width_, height_, size_, across_, count_;
};

}  // namespace tray
