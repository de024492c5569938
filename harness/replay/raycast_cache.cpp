#include "replay/raycast_cache.h"

#include <stb/stb_image.h>

#include <cctype>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <sstream>

#include "metrics/raycast.h"
#include "render/image_io.h"
#include "replay/measure_gpu.h"
#include "terrain/heightfield.h"

namespace lb {

// Word-wise FNV-1a variant: fast enough to run per measured frame on a 3601^2 DEM (~10 ms).
static uint64_t hashBytes(const void* data, size_t n, uint64_t h) {
  const auto* p = static_cast<const unsigned char*>(data);
  size_t i = 0;
  for (; i + 8 <= n; i += 8) {
    uint64_t w;
    std::memcpy(&w, p + i, 8);
    h = (h ^ w) * 0x100000001b3ull;
    h ^= h >> 29;
  }
  for (; i < n; ++i) h = (h ^ p[i]) * 0x100000001b3ull;
  return h;
}

static std::string cacheKey(const Heightfield& terrain, int width, int height, const CameraPose& pose) {
  uint64_t th = hashBytes(terrain.h.data(), terrain.h.size() * sizeof(float), 0xcbf29ce484222325ull);
  std::ostringstream key;
  key.precision(9);
  // Bump the version ("raycast2": normal-map shading; "raycast3": filtered at the footprint's mip
  // level) when the ray cast or terrain.frag's shading changes, so old files are not reused.
  key << "raycast3|" << std::hex << th << std::dec << '|' << terrain.width << 'x' << terrain.height << '|'
      << terrain.extent << '|' << terrain.originX << ',' << terrain.originZ << '|' << width << 'x' << height << '|'
      << pose.eye.x << ',' << pose.eye.y << ',' << pose.eye.z << '|' << pose.target.x << ',' << pose.target.y << ','
      << pose.target.z << '|' << pose.fovDeg;
  return key.str();
}

std::string ReferenceCache::file(const Heightfield& terrain, const std::string& terrainKey, int width, int height,
                                 const CameraPose& pose) const {
  if (dir_.empty()) return "";
  std::string label;
  for (char ch : terrainKey) label += std::isalnum(static_cast<unsigned char>(ch)) || ch == '-' ? ch : '_';
  std::string key = cacheKey(terrain, width, height, pose);
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx",
                (unsigned long long)hashBytes(key.data(), key.size(), 0x84222325cbf29ce4ull));
  return dir_ + "/" + label + "_" + std::to_string(width) + "x" + std::to_string(height) + "_" + hex + ".png";
}

const RgbaImage& ReferenceCache::image(Context&, const Heightfield& terrain, const std::string& terrainKey,
                                       const RenderSettings& settings, const CameraPose& pose) {
  return image(terrain, terrainKey, settings.width, settings.height, pose);
}

const RgbaImage& ReferenceCache::image(const Heightfield& terrain, const std::string& terrainKey, int width, int height,
                                       const CameraPose& pose) {
  std::string key = cacheKey(terrain, width, height, pose);
  auto it = images_.find(key);
  if (it != images_.end()) return it->second;
  std::string path = file(terrain, terrainKey, width, height, pose);
  if (!path.empty()) {
    int w = 0, h = 0, comp = 0;
    if (unsigned char* px = stbi_load(path.c_str(), &w, &h, &comp, 4)) {
      RgbaImage img{w, h, std::vector<uint8_t>(px, px + size_t(w) * size_t(h) * 4)};
      stbi_image_free(px);
      // Written atomically, so a file is whole; a size mismatch (never expected) means ray cast again.
      if (w == width && h == height) {
        ++loaded_;
        return images_[key] = std::move(img);
      }
    }
  }
  // The ray cast works in the heightfield's own frame; the pose is in world space (terrain origin).
  auto t0 = std::chrono::steady_clock::now();
  RgbaImage img = raycastImage(terrain, terrainLocalPose(pose, terrain), width, height);
  rayCastSeconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ++rayCasts_;
  if (!path.empty()) {
    std::filesystem::create_directories(dir_);
    writePng(path, width, height, img.px);
  }
  return images_[key] = std::move(img);
}

ReferenceCache::ReferenceCache() = default;
ReferenceCache::ReferenceCache(std::string dir) : dir_(std::move(dir)) {}
ReferenceCache::~ReferenceCache() = default;

MeasureGpu& ReferenceCache::gpu(Context& ctx, const Heightfield& terrain, const std::string& terrainKey, int width,
                                int height) {
  std::ostringstream key;
  key << terrainKey << '|' << terrain.width << 'x' << terrain.height << '|' << terrain.extent << '|' << width << 'x'
      << height;
  if (!gpu_ || gpuKey_ != key.str()) {
    gpu_.reset();  // the old buffers go before the new ones are made
    gpu_ = std::make_unique<MeasureGpu>(ctx, width, height);
    gpuKey_ = key.str();
  }
  return *gpu_;
}

}  // namespace lb
