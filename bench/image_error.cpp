#include "bench/image_error.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/error.h"

namespace tray {
namespace {

OIIO::ImageBuf beautyBuffer(const Film& f) {
  OIIO::ImageSpec spec(f.width(), f.height(), 4, OIIO::TypeDesc::FLOAT);
  // Wraps the film's memory; nothing is copied.
  return OIIO::ImageBuf(spec, const_cast<float*>(f.layers()[Film::kBeauty].data.data()));
}

}  // namespace

Film readReference(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw Error(path + ": cannot read the reference image");
  const int width = in->spec().width, height = in->spec().height;
  Film film(width, height);
  std::vector<float> rgb(size_t(width) * height * 3);
  if (!in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, rgb.data()))
    throw Error(path + ": " + in->geterror());
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c)
        film.pixel(Film::kBeauty, x, y)[c] = rgb[(size_t(y) * width + x) * 3 + c];
  return film;
}

Film readReferenceOfSize(const std::string& path, int width, int height) {
  Film film = readReference(path);
  if (film.width() != width || film.height() != height)
    throw Error(path + ": reference is " + std::to_string(film.width()) + "x" +
                std::to_string(film.height()) + ", the render " + std::to_string(width) + "x" +
                std::to_string(height) + " (use --resolution)");
  return film;
}

ImageError compareBeauty(const Film& a, const Film& b) {
  if (a.width() != b.width() || a.height() != b.height())
    throw Error("reference size " + std::to_string(b.width()) + "x" + std::to_string(b.height()) +
                " differs from the render's " + std::to_string(a.width()) + "x" +
                std::to_string(a.height()));
  OIIO::ImageBuf ba = beautyBuffer(a), bb = beautyBuffer(b);
  OIIO::ROI rgb = ba.roi();
  rgb.chbegin = 0, rgb.chend = 3;
  // RMSE and the largest difference from OIIO; relMSE and bias are not among its statistics.
  auto cmp = OIIO::ImageBufAlgo::compare(ba, bb, 0.0f, 0.0f, rgb);
  ImageError e;
  e.rmse = cmp.rms_error;
  e.maxAbs = cmp.maxerror;
  double sumA = 0, sumB = 0, rel = 0;
  std::vector<double> pixelRel;  // each pixel's relative squared error, summed over RGB
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x) {
      const float *pa = a.pixel(Film::kBeauty, x, y), *pb = b.pixel(Film::kBeauty, x, y);
      double pixel = 0;
      for (int c = 0; c < 3; ++c) {
        double d = double(pa[c]) - pb[c];
        pixel += d * d / (double(pb[c]) * pb[c] + 1e-2);
        sumA += pa[c], sumB += pb[c];
      }
      rel += pixel;
      pixelRel.push_back(pixel);
    }
  const double n = 3.0 * a.width() * a.height();
  e.relMse = rel / n;
  const size_t cut = std::max<size_t>(1, pixelRel.size() / 1000);
  std::nth_element(pixelRel.begin(), pixelRel.end() - cut, pixelRel.end());
  double kept = 0;
  for (size_t i = 0; i + cut < pixelRel.size(); ++i) kept += pixelRel[i];
  e.relMseTrimmed = pixelRel.size() > cut ? kept / (3.0 * double(pixelRel.size() - cut)) : 0;
  e.bias = (sumA - sumB) / n;
  return e;
}

}  // namespace tray
