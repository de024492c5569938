#include "render/image_io.h"

#include <zlib.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

// stb's own deflate leaves run images a third larger than zlib (kPngZlibLevel says by how much), so
// stb_image_write hands its filtered rows to zlib.
static unsigned char* zlibCompress(unsigned char* data, int length, int* outLength, int /*stbLevel*/) {
  uLongf size = compressBound(uLong(length));
  auto* out = static_cast<unsigned char*>(std::malloc(size));  // stb frees it with STBIW_FREE (free)
  if (out && compress2(out, &size, data, uLong(length), lb::kPngZlibLevel) != Z_OK) {
    std::free(out);
    out = nullptr;
  }
  *outLength = out ? int(size) : 0;
  return out;
}
#define STBIW_ZLIB_COMPRESS zlibCompress
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

namespace lb {

std::vector<uint8_t> opaqueRgb(const uint8_t* rgba, size_t pixels) {
  for (size_t i = 0; i < pixels; ++i)
    if (rgba[4 * i + 3] != 255) return {};
  std::vector<uint8_t> rgb(pixels * 3);
  for (size_t i = 0; i < pixels; ++i) std::copy(rgba + 4 * i, rgba + 4 * i + 3, &rgb[3 * i]);
  return rgb;
}

void writePng(const std::string& path, int width, int height, const std::vector<uint8_t>& rgba) {
  const size_t pixels = size_t(width) * size_t(height);
  if (rgba.size() < pixels * 4) throw std::runtime_error("writePng: too few pixels for " + path);
  // Opaque images (all of ours) go out as RGB: a quarter fewer bytes to compress, same pixels.
  std::vector<uint8_t> rgb = opaqueRgb(rgba.data(), pixels);
  const int channels = rgb.empty() ? 4 : 3;
  const uint8_t* px = rgb.empty() ? rgba.data() : rgb.data();
  std::string tmp = path + ".tmp";
  if (!stbi_write_png(tmp.c_str(), width, height, channels, px, width * channels))
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
