#include "terrain/generators.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "error.h"
#include "random.h"
#include "terrain/parallel_rows.h"

namespace lb {
namespace {

// A uniform int in [0, n) from the project's splitmix64 stream (random.h).
int below(SplitMix64& rng, int n) {
  return int(rng.below(size_t(n)));
}

// The ridged + fBm base of makeProcedural, rescaled to [0, peak].
Heightfield base(const TerrainSpec& spec, float peak) {
  TerrainSpec s = spec;
  s.type = "procedural";
  s.heightScale = peak;
  return makeProcedural(s);
}

}  // namespace

bool isGeneratedTerrain(const std::string& type) {
  return type == "spikes" || type == "cliff" || type == "flat" || type == "voids" || type == "canyon";
}

Heightfield makeGeneratedTerrain(const TerrainSpec& spec) {
  if (spec.type == "spikes") return makeSpikes(spec);
  if (spec.type == "cliff") return makeCliff(spec);
  if (spec.type == "flat") return makeFlat(spec);
  if (spec.type == "voids") return makeVoids(spec);
  if (spec.type == "canyon") return makeCanyon(spec);
  throw InputError("terrain: '" + spec.type + "' is not a generated terrain type (spikes, cliff, flat, voids, canyon)");
}

Heightfield makeSpikes(const TerrainSpec& spec) {
  Heightfield hf = base(spec, 0.1f * spec.heightScale);
  const int n = hf.width;
  const int count = std::max(1, (n / 64) * (n / 64));
  SplitMix64 rng{uint64_t(spec.seed) * 0x2545f4914f6cdd1dull + 1};
  std::vector<char> blocked(hf.h.size(), 0);
  for (int placed = 0, tries = 0; placed < count && tries < 64 * count; ++tries) {
    const int x = 2 + below(rng, std::max(1, n - 4)), z = 2 + below(rng, std::max(1, n - 4));
    if (x >= n - 1 || z >= n - 1 || blocked[size_t(z) * size_t(n) + size_t(x)]) continue;
    hf.h[size_t(z) * size_t(n) + size_t(x)] = spec.heightScale;
    // Keep spikes isolated: none within 2 samples of another.
    for (int dz = -2; dz <= 2; ++dz)
      for (int dx = -2; dx <= 2; ++dx) {
        const int bx = std::clamp(x + dx, 0, n - 1), bz = std::clamp(z + dz, 0, n - 1);
        blocked[size_t(bz) * size_t(n) + size_t(bx)] = 1;
      }
    ++placed;
  }
  hf.updateRange();
  return hf;
}

int cliffColumn(const TerrainSpec& spec) {
  SplitMix64 rng{uint64_t(spec.seed) * 0x9e3779b97f4a7c15ull + 7};
  const int third = std::max(1, (spec.size - 1) / 3);
  return third + below(rng, third);
}

Heightfield makeCliff(const TerrainSpec& spec) {
  Heightfield hf = base(spec, (1.0f - kCliffStep) * spec.heightScale);
  const int c = cliffColumn(spec);
  for (int z = 0; z < hf.height; ++z) {
    // Columns c and c + 1 share their base height, so the step between them is exactly the raise.
    float* row = &hf.h[size_t(z) * size_t(hf.width)];
    row[c + 1] = row[c];
  }
  for (int z = 0; z < hf.height; ++z)
    for (int x = c + 1; x < hf.width; ++x)
      hf.h[size_t(z) * size_t(hf.width) + size_t(x)] += kCliffStep * spec.heightScale;
  hf.updateRange();
  return hf;
}

Heightfield makeFlat(const TerrainSpec& spec) {
  Heightfield hf = base(spec, 0.0f);  // validates size and extent; heightScale 0 gives exact zeros
  std::fill(hf.h.begin(), hf.h.end(), 0.0f);
  hf.updateRange();
  return hf;
}

Heightfield makeCanyon(const TerrainSpec& spec) {
  Heightfield hf = base(spec, 1.0f);  // [0, 1], the crests at 1
  const size_t n = size_t(hf.width);
  parallelRows(
      hf.height,
      [&](int z0, int z1) {
        for (size_t i = size_t(z0) * n; i < size_t(z1) * n; ++i) {
          const float t = (1.0f - hf.h[i]) * float(kCanyonSteps);  // crests -> canyon floors
          const float step = std::min(std::floor(t), float(kCanyonSteps - 1));
          const float f = std::clamp((t - step - (1.0f - kCanyonWall)) / kCanyonWall, 0.0f, 1.0f);
          const float wall = f * f * (3.0f - 2.0f * f);  // smoothstep: flat bench, wall, flat bench
          hf.h[i] = std::min((step + wall) / float(kCanyonSteps) * spec.heightScale, spec.heightScale);
        }
      },
      256);
  hf.updateRange();
  return hf;
}

void writeHgtWithVoid(const std::string& file, uint32_t seed, int voidX, int voidZ, int voidSize) {
  constexpr int kN = 1201;
  TerrainSpec spec;
  spec.size = kN;
  spec.seed = seed;
  Heightfield hf = base(spec, 2000.0f);
  std::vector<unsigned char> bytes(size_t(kN) * kN * 2);
  for (int z = 0; z < kN; ++z)
    for (int x = 0; x < kN; ++x) {
      const bool inVoid = x >= voidX && x < voidX + voidSize && z >= voidZ && z < voidZ + voidSize;
      const int16_t m = inVoid ? int16_t(-32768) : int16_t(hf.h[size_t(z) * kN + size_t(x)] + 0.5f);
      const size_t i = size_t(z) * kN + size_t(x);
      bytes[2 * i] = uint8_t(uint16_t(m) >> 8);
      bytes[2 * i + 1] = uint8_t(uint16_t(m) & 0xff);
    }
  FILE* f = std::fopen(file.c_str(), "wb");
  if (!f) throw InputError("cannot write " + file);
  const size_t written = std::fwrite(bytes.data(), 1, bytes.size(), f);
  if (std::fclose(f) != 0 || written != bytes.size()) throw InputError("cannot write " + file);
}

}  // namespace lb

namespace lb {

Heightfield makeVoids(const TerrainSpec& spec) {
  // The loader reads files only, so the tile goes through a private temporary file: the fill is
  // then exactly what a real SRTM tile with voids gets.
  char name[] = "/tmp/lodbench-voids-XXXXXX";
  const int fd = mkstemp(name);
  if (fd < 0) throw InputError("terrain voids: cannot create a temporary file in /tmp");
  close(fd);
  const VoidPatch v = voidPatch(spec.seed);
  Heightfield hf;
  try {
    writeHgtWithVoid(name, spec.seed, v.x, v.z, v.size);
    TerrainSpec hgt = spec;
    hgt.type = "hgt";
    hgt.file = name;
    hf = loadHeightfield(hgt);
  } catch (...) {
    std::remove(name);
    throw;
  }
  std::remove(name);
  return hf;
}

VoidPatch voidPatch(uint32_t seed) {
  SplitMix64 rng{uint64_t(seed) * 0xd1b54a32d192ed03ull + 3};
  constexpr int kSize = 120;  // 10% of the tile side: a void the size of a small lake or a radar shadow
  return {300 + below(rng, 1201 - 600 - kSize), 300 + below(rng, 1201 - 600 - kSize), kSize};
}

}  // namespace lb
