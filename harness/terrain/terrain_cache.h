#pragma once
// A sweep reads a large terrain once. The config parser reads every file terrain to check it,
// then every case of the terrain needs it again; at 16385^2 each read (or generation) costs
// seconds, and a sweep of 20 cases read the same gigabyte 21 times. The last large terrain is
// kept and handed out shared; small terrains (the tests') are made anew each time.
#include <memory>

#include "terrain/heightfield.h"
#include "terrain/normal_map.h"

namespace lb {

// Terrains of at least this many samples are kept (2048^2: 16 MiB of heights).
constexpr long long kKeptTerrainSamples = 2048ll * 2048ll;

// makeHeightfield(spec), or the kept terrain when it was made from the same spec and, for a file,
// the file still has the size and modification time it had then. Thread-safe.
std::shared_ptr<const Heightfield> sharedHeightfield(const TerrainSpec& spec);

// computeNormalMap(hf), kept with the kept terrain when `hf` is it: every renderer of a tuned
// search builds one (a dozen per case), and at 32759^2 each map is 4 GiB and seconds of CPU.
// Thread-safe.
std::shared_ptr<const NormalMap> sharedNormalMap(const Heightfield& hf);

// The kept terrain when `hf` is it, else null: what a copy of it elsewhere (its pages on the
// device, render/device_terrain.h) may be kept against. Thread-safe.
std::shared_ptr<const Heightfield> keptHeightfield(const Heightfield& hf);

}  // namespace lb
