// libFuzzer target for one heightmap loader, chosen at build time (LB_FUZZ_TYPE: hgt, png16, r16,
// r32f). Bad input must end in lb::InputError, nothing else.
//  - r16 / r32f carry no header: the first byte picks the width (2..65), the height follows from
//    the rest's length, so most inputs reach the sample loop and the height checks.
//  - hgt files are only 1201^2 or 3601^2 samples: the input is fed as is (the size check), then
//    its first n^2 samples (n = floor(sqrt(size / 2))) go through decodeHgtGrid, the same decoder
//    (samples, voids and their fill, height checks) at side n. Tiling every input to 1201^2 as
//    before cost ~0.3 s per execution under ASan (100 executions in 30 s) and gave the fuzzer
//    only periodic grids; once per process a tiled 1201^2 input checks that decodeHeightfield
//    and decodeHgtGrid agree, so the real loader's path stays in the loop.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "error.h"
#include "terrain/heightfield.h"

#ifndef LB_FUZZ_TYPE
#error "define LB_FUZZ_TYPE"
#endif

static void decode(const lb::TerrainSpec& spec, const std::vector<unsigned char>& bytes) {
  try {
    lb::Heightfield h = lb::decodeHeightfield(spec, bytes);
    if (h.width < 2 || h.height < 2 || h.h.size() != size_t(h.width) * size_t(h.height)) __builtin_trap();
    (void)h.sample(h.extent * 0.5f, h.extent * 0.25f);
  } catch (const lb::InputError&) {
  }
}

static void checkField(const lb::Heightfield& h) {
  if (h.width < 2 || h.height < 2 || h.h.size() != size_t(h.width) * size_t(h.height)) __builtin_trap();
  for (float v : h.h)
    if (!(v >= h.minHeight && v <= h.maxHeight)) __builtin_trap();  // voids filled, range updated
}

static void decodeGrid(const lb::TerrainSpec& spec, const std::vector<unsigned char>& bytes, int side) {
  try {
    checkField(lb::decodeHgtGrid(spec, bytes, side));
  } catch (const lb::InputError&) {
  }
}

// decodeHeightfield (size check, then the decoder) and decodeHgtGrid at 1201 must give the same
// field, or both refuse: the small grids fuzzed above run the loader's own code.
static void compareWithLoader(const lb::TerrainSpec& spec, const uint8_t* data, size_t size) {
  std::vector<unsigned char> tiled(size_t(1201) * 1201 * 2);
  for (size_t i = 0; i < tiled.size(); ++i) tiled[i] = data[i % size];
  lb::Heightfield a, b;
  bool aOk = true, bOk = true;
  try {
    a = lb::decodeHeightfield(spec, tiled);
  } catch (const lb::InputError&) {
    aOk = false;
  }
  try {
    b = lb::decodeHgtGrid(spec, tiled, 1201);
  } catch (const lb::InputError&) {
    bOk = false;
  }
  if (aOk != bOk || (aOk && (a.h != b.h || a.width != b.width || a.minHeight != b.minHeight))) __builtin_trap();
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  lb::TerrainSpec spec;
  spec.type = LB_FUZZ_TYPE;
  spec.file = "fuzz." + spec.type;
  spec.heightScale = 1.0f;
  std::vector<unsigned char> bytes(data, data + size);
  if (spec.type == "r16" || spec.type == "r32f") {
    if (size < 1) return 0;
    const size_t bps = spec.type == "r16" ? 2 : 4;
    spec.rawWidth = 2 + data[0] % 64;
    bytes.erase(bytes.begin());
    spec.rawHeight = int(bytes.size() / (size_t(spec.rawWidth) * bps));
    if (spec.rawHeight > 65536) return 0;
  }
  decode(spec, bytes);
  if (spec.type == "hgt") {
    size_t n = 0;
    while ((n + 1) * (n + 1) * 2 <= size) ++n;
    if (n >= 2) {
      bytes.resize(n * n * 2);
      decodeGrid(spec, bytes, int(n));
      static bool compared = false;
      if (!compared) {
        compared = true;
        compareWithLoader(spec, data, size);
      }
    }
  }
  return 0;
}
