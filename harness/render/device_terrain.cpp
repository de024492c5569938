#include "render/device_terrain.h"

#include <chrono>

#include "terrain/heightfield.h"
#include "terrain/normal_map.h"
#include "terrain/terrain_cache.h"
#include "vk/context.h"

namespace lb {
namespace {

// What Context::keptTerrain holds: the copy and the host terrain it was made from. The weak
// reference expires when the terrain cache lets that terrain go, so a later terrain made at the
// same address never matches.
struct KeptCopy {
  std::weak_ptr<const Heightfield> terrain;
  std::shared_ptr<const DeviceTerrain> copy;
};

double secondsSince(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

std::shared_ptr<DeviceTerrain> makeCopy(Context& ctx, const Heightfield& hf, const DeviceTerrainOptions& o) {
  auto copy = std::make_shared<DeviceTerrain>();
  const auto tPages = std::chrono::steady_clock::now();
  copy->heights = createHeightPages(ctx, hf, {GpuResource::Heights, &copy->memory}, o.heightDefect, o.heightLayers);
  copy->pagesS = secondsSince(tPages);
  const auto tNormals = std::chrono::steady_clock::now();
  const std::shared_ptr<const NormalMap> normals = sharedNormalMap(hf);
  copy->normalMapS = secondsSince(tNormals);
  copy->normals = createNormalPages(ctx, *normals, {GpuResource::NormalMap, &copy->memory}, o.normalCells,
                                    o.normalLayers, o.normalDefect, o.normalCoarseFrom);
  return copy;
}

}  // namespace

bool DeviceTerrainOptions::shareable() const {
  return heightDefect == PageDefect::None && heightLayers == 0 && normalCells == 0 && normalLayers == 0 &&
         normalDefect == NormalPageDefect::None && normalCoarseFrom == 0;
}

std::shared_ptr<const DeviceTerrain> deviceTerrain(Context& ctx, const Heightfield& hf,
                                                   const DeviceTerrainOptions& options, bool* reused) {
  if (reused) *reused = false;
  auto* kept = static_cast<KeptCopy*>(ctx.keptTerrain.get());
  // The terrain cache let the kept copy's terrain go: so does the device (renderers still using
  // the copy keep it alive until they end).
  if (kept && kept->terrain.expired()) {
    ctx.keptTerrain.reset();
    kept = nullptr;
  }
  const std::shared_ptr<const Heightfield> host = options.shareable() ? keptHeightfield(hf) : nullptr;
  if (kept && host && kept->terrain.lock() == host) {
    if (reused) *reused = true;
    return kept->copy;
  }
  if (!host) return makeCopy(ctx, hf, options);
  ctx.keptTerrain.reset();  // before the new copy: never two large copies at once on this account
  auto next = std::make_shared<KeptCopy>();
  next->terrain = host;
  next->copy = makeCopy(ctx, hf, options);
  ctx.keptTerrain = next;
  return next->copy;
}

}  // namespace lb
