#include "render/image_io.h"

#include <cstdio>
#include <stdexcept>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

namespace lb {

void writePng(const std::string& path, int width, int height, const std::vector<uint8_t>& rgba) {
  if (rgba.size() < size_t(width) * size_t(height) * 4) throw std::runtime_error("writePng: too few pixels for " + path);
  std::string tmp = path + ".tmp";
  if (!stbi_write_png(tmp.c_str(), width, height, 4, rgba.data(), width * 4))
    throw std::runtime_error("cannot write " + path);
  if (std::rename(tmp.c_str(), path.c_str()) != 0) throw std::runtime_error("cannot rename " + tmp + " to " + path);
}

}  // namespace lb
