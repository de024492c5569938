#include "terrain/normal_map.h"

#include <cpuid.h>
#include <immintrin.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "shaders/footprint.h"
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
  // Every half is a float exactly: a normal one by moving its fields (the exponent rebiased from 15
  // to 127, the mantissa 13 bits up), a subnormal one as mant x 2^-24 (a power of two: exact). No
  // ldexp: it was a library call per texel, most of the coarse levels' time.
  const uint32_t sign = uint32_t(h & 0x8000) << 16, exp = (h >> 10) & 0x1fu, mant = h & 0x3ffu;
  float f;
  if (exp == 0) {
    f = float(mant) * 5.9604644775390625e-8f;  // 2^-24
    uint32_t bits;
    std::memcpy(&bits, &f, 4);
    bits |= sign;
    std::memcpy(&f, &bits, 4);
    return f;
  }
  const uint32_t bits = sign | (exp + 112u) << 23 | mant << 13;  // exp 31 (inf) never stored
  std::memcpy(&f, &bits, 4);
  return f;
}

namespace {

// The processor converts float to half itself (F16C, with AVX): its round to nearest even is
// floatToHalf's, so the lanes below give the same bits, once the magnitude is clamped as there.
// F16C is read from CPUID (leaf 1, ECX bit 29): clang's __builtin_cpu_supports has no "f16c".
bool halfLanes() {
  unsigned a = 0, b = 0, c = 0, d = 0;
  return __builtin_cpu_supports("avx") && __get_cpuid(1, &a, &b, &c, &d) && (c & (1u << 29)) != 0;
}

__attribute__((target("avx,f16c"))) inline __m128i toHalf8(__m256 f) {
  const __m256 sign = _mm256_set1_ps(-0.0f);
  const __m256 mag = _mm256_min_ps(_mm256_andnot_ps(sign, f), _mm256_set1_ps(65504.0f));
  return _mm256_cvtps_ph(_mm256_or_ps(mag, _mm256_and_ps(sign, f)), _MM_FROUND_TO_NEAREST_INT);
}

// Level 0's texels x in [1, 1 + 8k) of one row (each with both neighbours inside the row): the
// same float operations as the scalar texel, eight at a time; returns 8k.
__attribute__((target("avx,f16c"))) int gradientLanes(const float* row, const float* up, const float* down,
                                                      uint16_t* out, int w, float dx, float dz) {
  const __m256 vdx = _mm256_set1_ps(dx), vdz = _mm256_set1_ps(dz);
  int x = 1;
  for (; x + 8 <= w - 1; x += 8) {
    const __m256 gx = _mm256_div_ps(_mm256_sub_ps(_mm256_loadu_ps(row + x - 1), _mm256_loadu_ps(row + x + 1)), vdx);
    const __m256 gz = _mm256_div_ps(_mm256_sub_ps(_mm256_loadu_ps(up + x), _mm256_loadu_ps(down + x)), vdz);
    const __m128i hx = toHalf8(gx), hz = toHalf8(gz);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + 2 * size_t(x)), _mm_unpacklo_epi16(hx, hz));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + 2 * size_t(x) + 8), _mm_unpackhi_epi16(hx, hz));
  }
  return x - 1;
}

__attribute__((target("avx,f16c"))) inline __m256 load(const uint16_t* p) {
  return _mm256_cvtph_ps(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p)));
}

// One coarse row's texels [0, 4k) from two fine rows, each the mean of 2 x 2 fine texels summed
// in the scalar order (row by row, left to right, from 0): texel pairs (gx, gz) are the lanes, the
// even and odd fine texels of four coarse texels come out as coarse texels 0, 2, 1, 3 and go back
// in order after the conversion. Returns 4k (at most `count`, the coarse texels with two fine ones).
__attribute__((target("avx,f16c"))) int halveLanes(const uint16_t* f0, const uint16_t* f1, uint16_t* out, int count) {
  const __m256 four = _mm256_set1_ps(4.0f);
  int x = 0;
  for (; x + 4 <= count; x += 4) {
    const uint16_t* a = f0 + 4 * size_t(x);  // 8 fine texels, 16 halves, from fine texel 2x
    const uint16_t* b = f1 + 4 * size_t(x);
    const __m256d a0 = _mm256_castps_pd(load(a)), a1 = _mm256_castps_pd(load(a + 8));
    const __m256d b0 = _mm256_castps_pd(load(b)), b1 = _mm256_castps_pd(load(b + 8));
    __m256 sum = _mm256_setzero_ps();
    sum = _mm256_add_ps(sum, _mm256_castpd_ps(_mm256_shuffle_pd(a0, a1, 0x0)));  // row 0, even
    sum = _mm256_add_ps(sum, _mm256_castpd_ps(_mm256_shuffle_pd(a0, a1, 0xf)));  // row 0, odd
    sum = _mm256_add_ps(sum, _mm256_castpd_ps(_mm256_shuffle_pd(b0, b1, 0x0)));  // row 1, even
    sum = _mm256_add_ps(sum, _mm256_castpd_ps(_mm256_shuffle_pd(b0, b1, 0xf)));  // row 1, odd
    const __m128i h = toHalf8(_mm256_div_ps(sum, four));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + 2 * size_t(x)), _mm_shuffle_epi32(h, _MM_SHUFFLE(3, 1, 2, 0)));
  }
  return x;
}

}  // namespace

bool normalMapLanes() {
  return halfLanes();
}

static void addCoarserLevels(NormalMap& nm, bool lanes);

NormalMap computeNormalMap(const Heightfield& hf, bool lanes) {
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
  const float dx = 2.0f * tx, dz = 2.0f * tz;
  const bool f16c = lanes && halfLanes();
  parallelRows(h, [&](int z0, int z1) {
    for (int z = z0; z < z1; ++z) {
      const float* row = &hf.h[size_t(z) * size_t(w)];
      const float* up = &hf.h[size_t(std::max(z - 1, 0)) * size_t(w)];
      const float* down = &hf.h[size_t(std::min(z + 1, h - 1)) * size_t(w)];
      uint16_t* out = &nm.texels[size_t(z) * size_t(w) * 2];
      // Texels [1, end) eight at a time where the processor converts to half itself; the rest here.
      const int end = f16c && w > 2 ? 1 + gradientLanes(row, up, down, out, w, dx, dz) : 1;
      auto one = [&](int x) {
        const int left = x > 0 ? x - 1 : 0, right = x + 1 < w ? x + 1 : w - 1;
        out[2 * size_t(x)] = floatToHalf((row[left] - row[right]) / dx);
        out[2 * size_t(x) + 1] = floatToHalf((up[x] - down[x]) / dz);
      };
      one(0);
      for (int x = end; x < w; ++x) one(x);
    }
  });
  addCoarserLevels(nm, lanes);
  return nm;
}

// Level k from level k - 1: the mean of the texels each covers (the last one of an odd row or
// column joins the texel before it), in float, rounded to half.
static NormalMapLevel halve(int w, int h, const UninitVector<uint16_t>& fine, bool lanes) {
  NormalMapLevel out;
  out.width = std::max(1, w / 2);
  out.height = std::max(1, h / 2);
  out.texels.resize(size_t(out.width) * size_t(out.height) * 2);
  auto span = [](int i, int n, int fineN) {  // the fine texels [first, last] of coarse texel i
    const int first = 2 * i;
    const int last = i == n - 1 ? fineN - 1 : std::min(2 * i + 1, fineN - 1);
    return std::pair<int, int>(first, last);
  };
  const bool f16c = lanes && halfLanes();
  parallelRows(out.height, [&](int z0, int z1) {
    for (int z = z0; z < z1; ++z) {
      const auto [za, zb] = span(z, out.height, h);
      // Coarse texels of two fine rows and two fine columns (all but an odd size's last) in lanes.
      const int pairs = std::min(out.width, w / 2);
      const int from = f16c && zb == za + 1 && w >= 2
                           ? halveLanes(&fine[size_t(za) * size_t(w) * 2], &fine[size_t(zb) * size_t(w) * 2],
                                        &out.texels[size_t(z) * size_t(out.width) * 2],
                                        pairs == out.width && w % 2 ? pairs - 1 : pairs)
                           : 0;
      for (int x = from; x < out.width; ++x) {
        const auto [xa, xb] = span(x, out.width, w);
        float gx = 0, gz = 0;
        for (int j = za; j <= zb; ++j)
          for (int i = xa; i <= xb; ++i) {
            const size_t k = (size_t(j) * size_t(w) + size_t(i)) * 2;
            gx += halfToFloat(fine[k]);
            gz += halfToFloat(fine[k + 1]);
          }
        const float n = float((zb - za + 1) * (xb - xa + 1));
        const size_t o = (size_t(z) * size_t(out.width) + size_t(x)) * 2;
        out.texels[o] = floatToHalf(gx / n);
        out.texels[o + 1] = floatToHalf(gz / n);
      }
    }
  });
  return out;
}

static void addCoarserLevels(NormalMap& nm, bool lanes) {
  const int levels = normalMapLevels(nm.width, nm.height);
  for (int k = 1; k < levels; ++k)
    nm.coarser.push_back(halve(nm.levelWidth(k - 1), nm.levelHeight(k - 1), nm.levelTexels(k - 1), lanes));
}

// One level's bilinear fetch at texel coordinate u (texel i's centre at i), clamped to the edge.
static glm::vec2 bilinear(const NormalMap& nm, int k, glm::vec2 u) {
  const int w = nm.levelWidth(k), h = nm.levelHeight(k);
  const auto& texels = nm.levelTexels(k);
  const glm::vec2 fl = glm::floor(u);
  const glm::vec2 f = u - fl;
  const glm::ivec2 i0(fl);
  const glm::ivec2 a = glm::clamp(i0, glm::ivec2(0), glm::ivec2(w - 1, h - 1));
  const glm::ivec2 b = glm::clamp(i0 + 1, glm::ivec2(0), glm::ivec2(w - 1, h - 1));
  auto g = [&](int ix, int iz) {
    size_t i = (size_t(iz) * size_t(w) + size_t(ix)) * 2;
    return glm::vec2(halfToFloat(texels[i]), halfToFloat(texels[i + 1]));
  };
  return glm::mix(glm::mix(g(a.x, a.y), g(b.x, a.y), f.x), glm::mix(g(a.x, b.y), g(b.x, b.y), f.x), f.y);
}

glm::vec3 sampleNormalMap(const NormalMap& nm, float extent, float x, float z, float level) {
  const glm::ivec2 size(nm.width, nm.height);
  const glm::vec2 t = glm::clamp(glm::vec2(x, z) / extent, 0.0f, 1.0f) * glm::vec2(size - 1);
  // Level k's texel coordinate: (t + 0.5) / size0 * size_k - 0.5 (level 0: t itself).
  auto at = [&](int k) {
    if (k == 0) return t;
    const glm::vec2 sk(float(nm.levelWidth(k)), float(nm.levelHeight(k)));
    return (t + 0.5f) * sk / glm::vec2(size) - 0.5f;
  };
  const int last = nm.levels() - 1;
  const float clamped = std::clamp(level, 0.0f, float(last));
  const int k0 = int(std::floor(clamped));
  const float f = clamped - float(k0);
  glm::vec2 s = bilinear(nm, k0, at(k0));
  if (f > 0.0f) s = glm::mix(s, bilinear(nm, k0 + 1, at(k0 + 1)), f);
  return glm::normalize(glm::vec3(s.x, 1.0f, s.y));
}

}  // namespace lb
