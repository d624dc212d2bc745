#pragma once
// Reading an EXR back in tests, independently of io/image_input (which reads only what TRay
// writes): the spec as OIIO sees it and every channel as float.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

namespace tray::test {

/// An EXR read back whole: spec and every channel as float (half converts exactly).
struct Exr {
  OIIO::ImageSpec spec;
  std::vector<float> pixels;  ///< interleaved, spec.nchannels per pixel
  int channel(const std::string& name) const {
    for (int c = 0; c < spec.nchannels; ++c)
      if (spec.channelnames[c] == name) return c;
    return -1;
  }
  float at(int x, int y, const std::string& name) const {
    return pixels[(size_t(y) * spec.width + x) * spec.nchannels + channel(name)];
  }
};

inline Exr readExrFile(const std::filesystem::path& path) {
  Exr e;
  auto in = OIIO::ImageInput::open(path.string());
  EXPECT_TRUE(in) << path << ": " << OIIO::geterror();
  if (!in) return e;
  e.spec = in->spec();
  e.pixels.resize(size_t(e.spec.width) * e.spec.height * e.spec.nchannels);
  EXPECT_TRUE(in->read_image(0, 0, 0, e.spec.nchannels, OIIO::TypeDesc::FLOAT, e.pixels.data()))
      << path << ": " << in->geterror();
  return e;
}

}  // namespace tray::test
