#pragma once
// Hostile procedural terrains for the scenario library ("hostile terrain"): seeded and
// deterministic like makeProcedural (same spec -> same bits). Each provokes a failure the seeds
// predict: one-texel spikes that screen-space and distance rules cannot see, a cliff that a
// plane fit or a density map must catch within one texel, and a flat plane on which every
// error metric must read exactly zero.
#include <cstdint>
#include <string>

#include "terrain/heightfield.h"

namespace lb {

// Terrain types these generators add to TerrainSpec::type.
bool isGeneratedTerrain(const std::string& type);  // spikes | cliff | flat | voids | canyon
// Dispatches on spec.type; throws InputError for a size outside makeProcedural's range.
Heightfield makeGeneratedTerrain(const TerrainSpec& spec);

// Gentle ridged ground at 10% of heightScale with isolated one-texel spikes of full height:
// one spike per 64x64 texels at seeded positions, never on the border or next to another.
Heightfield makeSpikes(const TerrainSpec& spec);
// Ridged ground in [0, 0.7 heightScale] and, east of a seeded column in the middle third, raised
// by kCliffStep * heightScale: a vertical step of at least 30% of the height range between two
// adjacent samples (one texel), running the whole length of the terrain along z.
constexpr float kCliffStep = 0.3f;
Heightfield makeCliff(const TerrainSpec& spec);
int cliffColumn(const TerrainSpec& spec);  // the last sample column before the step
// Every sample 0: a perfectly flat plane (heightScale ignored).
Heightfield makeFlat(const TerrainSpec& spec);
// Canyon country, a terrain of another character than the procedural mountains for the workload
// suite (configs/suite/): the procedural terrain (its "detail" included) upside down, so its sharp
// crests become narrow canyons cut into broad uplands, then terraced into kCanyonSteps flat benches
// joined by walls that rise over the top kCanyonWall of each step (5x steeper than the slope they
// replace at their middle). Heights in [0, heightScale]; same spec -> same bits.
constexpr int kCanyonSteps = 5;
constexpr float kCanyonWall = 0.3f;
Heightfield makeCanyon(const TerrainSpec& spec);

// An SRTM tile (1201^2, writeHgtWithVoid) with a seeded void patch, read back through the .hgt
// loader so its voids are filled as loadHeightfield documents; `size` is ignored (the tile's is
// 1201), heightScale multiplies the stored metres as for hgt files (default 1 for this type).
Heightfield makeVoids(const TerrainSpec& spec);
struct VoidPatch {
  int x = 0, z = 0, size = 0;  // top-left sample and side, in samples
};
VoidPatch voidPatch(uint32_t seed);

// Test input for the SRTM loader's void filling: a 1201x1201 .hgt (big-endian int16) of a seeded
// ridged terrain in [0, 2000] m with a void patch (-32768) of voidSize^2 samples whose top-left
// sample is (voidX, voidZ). Writes atomically enough for tests (one write, then close).
void writeHgtWithVoid(const std::string& file, uint32_t seed, int voidX, int voidZ, int voidSize);

}  // namespace lb
