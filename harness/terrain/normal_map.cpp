#include "terrain/normal_map.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "terrain/heightfield.h"
#include "terrain/parallel_rows.h"

namespace lb {

uint16_t floatToHalf(float f) {
  uint32_t x;
  std::memcpy(&x, &f, 4);
  const uint16_t sign = uint16_t((x >> 16) & 0x8000u);
  float a = std::min(std::fabs(f), 65504.0f);  // largest finite half; NaN never occurs (finite heights)
  std::memcpy(&x, &a, 4);
  int exp = int((x >> 23) & 0xff) - 127;
  uint32_t mant = x & 0x7fffffu;
  if (exp < -25) return sign;  // below half the smallest subnormal: rounds to zero
  uint32_t h;
  int shift;
  if (exp < -14) {  // subnormal half: mantissa with the implicit bit, shifted further
    mant |= 0x800000u;
    shift = 13 + (-14 - exp);
    h = 0;
  } else {
    shift = 13;
    h = uint32_t(exp + 15) << 10;
  }
  uint32_t q = mant >> shift, rem = mant & ((1u << shift) - 1), halfway = 1u << (shift - 1);
  if (rem > halfway || (rem == halfway && (q & 1))) ++q;  // carries into the exponent correctly
  return uint16_t(sign | (h + q));
}

float halfToFloat(uint16_t h) {
  const float sign = h & 0x8000 ? -1.0f : 1.0f;
  int exp = (h >> 10) & 0x1f, mant = h & 0x3ff;
  if (exp == 0) return sign * std::ldexp(float(mant), -24);
  return sign * std::ldexp(float(mant | 0x400), exp - 25);  // exp 31 (inf) never stored
}

NormalMap computeNormalMap(const Heightfield& hf) {
  NormalMap nm;
  nm.width = hf.width;
  nm.height = hf.height;
  nm.texels.resize(size_t(hf.width) * size_t(hf.height) * 2);
  // As common.glsl terrainNormal() at a sample point: neighbours one texel apart, clamped to the border.
  const float tx = hf.extent / float(std::max(hf.width - 1, 1)), tz = hf.extent / float(std::max(hf.height - 1, 1));
  // Rows are independent: bands on every hardware thread give the same texels as one thread.
  // Neighbours are read through row pointers with the border clamp of Heightfield::at() done once
  // per row and column, not per read: the same samples, so the same texels.
  const int w = hf.width, h = hf.height;
  parallelRows(h, [&](int z0, int z1) {
    for (int z = z0; z < z1; ++z) {
      const float* row = &hf.h[size_t(z) * size_t(w)];
      const float* up = &hf.h[size_t(std::max(z - 1, 0)) * size_t(w)];
      const float* down = &hf.h[size_t(std::min(z + 1, h - 1)) * size_t(w)];
      uint16_t* out = &nm.texels[size_t(z) * size_t(w) * 2];
      for (int x = 0; x < w; ++x) {
        const int left = x > 0 ? x - 1 : 0, right = x + 1 < w ? x + 1 : w - 1;
        float gx = (row[left] - row[right]) / (2.0f * tx);
        float gz = (up[x] - down[x]) / (2.0f * tz);
        out[2 * size_t(x)] = floatToHalf(gx);
        out[2 * size_t(x) + 1] = floatToHalf(gz);
      }
    }
  });
  return nm;
}

glm::vec3 sampleNormalMap(const NormalMap& nm, float extent, float x, float z) {
  const glm::ivec2 size(nm.width, nm.height);
  glm::vec2 t = glm::clamp(glm::vec2(x, z) / extent, 0.0f, 1.0f) * glm::vec2(size - 1);
  glm::ivec2 i0 = glm::min(glm::ivec2(glm::floor(t)), glm::max(size - 2, glm::ivec2(0)));
  glm::vec2 f = t - glm::vec2(i0);
  glm::ivec2 i1 = glm::min(i0 + 1, size - 1);
  auto g = [&](int ix, int iz) {
    size_t i = (size_t(iz) * size_t(nm.width) + size_t(ix)) * 2;
    return glm::vec2(halfToFloat(nm.texels[i]), halfToFloat(nm.texels[i + 1]));
  };
  glm::vec2 s = glm::mix(glm::mix(g(i0.x, i0.y), g(i1.x, i0.y), f.x), glm::mix(g(i0.x, i1.y), g(i1.x, i1.y), f.x), f.y);
  return glm::normalize(glm::vec3(s.x, 1.0f, s.y));
}

}  // namespace lb
