// libFuzzer target for one heightmap loader, chosen at build time (LB_FUZZ_TYPE: hgt, png16, r16,
// r32f). Bad input must end in lb::InputError, nothing else.
//  - r16 / r32f carry no header: the first byte picks the width (2..65), the height follows from
//    the rest's length, so most inputs reach the sample loop and the height checks.
//  - hgt accepts only 1201^2 or 3601^2 samples: the input is fed as is (size check) and, tiled to
//    1201^2 samples, again (decoding, voids and their fill).
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
  if (spec.type == "hgt" && size > 0 && size < 1201 * 1201 * 2) {
    std::vector<unsigned char> tiled(size_t(1201) * 1201 * 2);
    for (size_t i = 0; i < tiled.size(); ++i) tiled[i] = data[i % size];
    decode(spec, tiled);
  }
  return 0;
}
