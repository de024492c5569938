#include "render/image_io.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

namespace lb {

void writePng(const std::string& path, int width, int height, const std::vector<uint8_t>& rgba) {
  if (rgba.size() < size_t(width) * size_t(height) * 4)
    throw std::runtime_error("writePng: too few pixels for " + path);
  std::string tmp = path + ".tmp";
  if (!stbi_write_png(tmp.c_str(), width, height, 4, rgba.data(), width * 4))
    throw std::runtime_error("cannot write " + path);
  if (std::rename(tmp.c_str(), path.c_str()) != 0) throw std::runtime_error("cannot rename " + tmp + " to " + path);
}

}  // namespace lb

namespace lb {

std::vector<uint8_t> scaleNearest(const std::vector<uint8_t>& src, int width, int height, int channels, int outWidth,
                                  int outHeight) {
  if (width < 1 || height < 1 || outWidth < 1 || outHeight < 1 || channels < 1 ||
      src.size() != size_t(width) * size_t(height) * size_t(channels))
    throw std::invalid_argument("scaleNearest: image size and pixel count disagree");
  std::vector<uint8_t> out(size_t(outWidth) * size_t(outHeight) * size_t(channels));
  for (int y = 0; y < outHeight; ++y) {
    // Integer form of floor((y + 0.5) * height / outHeight): exact, so a 2x scale repeats each pixel twice.
    size_t sy = size_t((2 * int64_t(y) + 1) * height / (2 * int64_t(outHeight)));
    for (int x = 0; x < outWidth; ++x) {
      size_t sx = size_t((2 * int64_t(x) + 1) * width / (2 * int64_t(outWidth)));
      const uint8_t* s = &src[(sy * size_t(width) + sx) * size_t(channels)];
      std::copy(s, s + channels, &out[(size_t(y) * size_t(outWidth) + size_t(x)) * size_t(channels)]);
    }
  }
  return out;
}

}  // namespace lb
