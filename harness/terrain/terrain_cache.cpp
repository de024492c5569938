#include "terrain/terrain_cache.h"

#include <filesystem>
#include <mutex>
#include <sstream>
#include <string>

namespace lb {
namespace {

// Every field that changes the heights or their pages, and the file's identity on disk.
std::string keyOf(const TerrainSpec& s) {
  std::ostringstream k;
  k.precision(17);
  k << s.type << '\n'
    << s.file << '\n'
    << s.size << ' ' << s.seed << ' ' << s.rawWidth << ' ' << s.rawHeight << ' ' << s.extent << ' ' << s.heightScale
    << ' ' << s.originX << ' ' << s.originZ << ' ' << s.detailToSpacing << ' ' << s.band << ' ' << s.overview << ' '
    << s.page;
  for (int v : s.window) k << ' ' << v;
  if (!s.file.empty()) {
    std::error_code ec;
    const auto size = std::filesystem::file_size(s.file, ec);
    const auto time = std::filesystem::last_write_time(s.file, ec);
    if (ec) return "";  // unreadable now: never matches, so the loader reports it
    k << '\n' << size << ' ' << time.time_since_epoch().count();
  }
  return k.str();
}

std::mutex gMutex;
std::string gKey;
std::shared_ptr<const Heightfield> gKept;
std::shared_ptr<const NormalMap> gKeptNormals;  // of gKept, made on first request

}  // namespace

std::shared_ptr<const Heightfield> sharedHeightfield(const TerrainSpec& spec) {
  const std::string key = keyOf(spec);
  {
    std::lock_guard<std::mutex> lock(gMutex);
    if (gKept && !key.empty() && key == gKey) return gKept;
    // Another terrain: let the kept one go first, so two large terrains never sit in memory at
    // once on its account (a caller still holding it keeps it alive, as it must).
    gKept.reset();
    gKeptNormals.reset();
    gKey.clear();
  }
  auto made = std::make_shared<const Heightfield>(makeHeightfield(spec));
  if (!key.empty() && (long long)made->width * made->height >= kKeptTerrainSamples) {
    std::lock_guard<std::mutex> lock(gMutex);
    gKey = key;
    gKept = made;
  }
  return made;
}

std::shared_ptr<const NormalMap> sharedNormalMap(const Heightfield& hf) {
  {
    std::lock_guard<std::mutex> lock(gMutex);
    if (gKept.get() != &hf) return std::make_shared<const NormalMap>(computeNormalMap(hf));
    if (gKeptNormals) return gKeptNormals;
  }
  // Computed outside the lock: two threads asking at once both compute it, and the same map wins.
  auto made = std::make_shared<const NormalMap>(computeNormalMap(hf));
  std::lock_guard<std::mutex> lock(gMutex);
  if (gKept.get() == &hf && !gKeptNormals) gKeptNormals = made;
  return made;
}

std::shared_ptr<const Heightfield> keptHeightfield(const Heightfield& hf) {
  std::lock_guard<std::mutex> lock(gMutex);
  return gKept.get() == &hf ? gKept : nullptr;
}

}  // namespace lb
