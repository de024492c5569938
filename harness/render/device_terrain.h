#pragma once
// The terrain's device copy: its height pages and its normal map, which every renderer of the
// terrain binds and none changes. A renderer of a large terrain takes the copy kept from the one
// before it: a sweep builds a renderer per case and per configuration its tuned search tries, and
// at 65537^2 each copy is 17 GB of height pages and 21 GB of normal pages cut and uploaded again,
// about a minute a case on 16 cores. Small terrains (every test's) get a copy of their own.
#include <memory>

#include "render/height_pages.h"
#include "render/normal_pages.h"
#include "vk/gpu_memory.h"

namespace lb {

struct Context;
struct Heightfield;

struct DeviceTerrain {
  GpuMemoryAccount memory;  // before the resources: they give their charges back to it
  HeightPages heights;
  NormalPages normals;
  double pagesS = 0;      // cutting and uploading the height pages
  double normalMapS = 0;  // computing the normal map (or taking the kept one), not its upload
};

// Options that change the copy; anything but the defaults is a test's and never shared.
struct DeviceTerrainOptions {
  PageDefect heightDefect = PageDefect::None;
  uint32_t heightLayers = 0;
  int normalCells = 0;
  uint32_t normalLayers = 0;
  NormalPageDefect normalDefect = NormalPageDefect::None;
  int normalCoarseFrom = 0;
  bool shareable() const;
};

// The copy of `hf` kept on `ctx` when hf is the kept terrain (terrain/terrain_cache.h) and the
// options are the defaults; else a new copy (kept on ctx in its turn when shareable). `reused`
// says which. The copy kept before is released before a new one is made, so two large terrains
// are never on the device at once on the cache's account. Not thread-safe: one renderer is built
// at a time per context.
std::shared_ptr<const DeviceTerrain> deviceTerrain(Context& ctx, const Heightfield& hf,
                                                   const DeviceTerrainOptions& options, bool* reused = nullptr);

}  // namespace lb
