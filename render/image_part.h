#pragma once
// The part of an image a render covers: a region of its pixels and a range of each pixel's
// samples (farm renders split jobs by either; docs/farm.md).

namespace tray {

/// Pixels x0 <= x < x1, y0 <= y < y1 of the full image.
struct PixelRegion {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
};

/// Samples begin <= i < end of every pixel.
struct SampleRange {
  int begin = 0, end = 0;
};

}  // namespace tray
