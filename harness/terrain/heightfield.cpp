#include "terrain/heightfield.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "error.h"
#include "terrain/generators.h"
#include "terrain/parallel_rows.h"

// makeProcedural promises the same bits on every machine. Fusing a*b+c into an FMA rounds once
// instead of twice, so a compiler that contracts (GCC's default in gnu++ mode on FMA targets,
// Clang's default everywhere) would make ARM and x86 terrains differ. Forbid it for this file.
#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#elif defined(__GNUC__)
#pragma GCC optimize("fp-contract=off")
#endif

namespace lb {

float Heightfield::at(int x, int z) const {
  x = std::clamp(x, 0, width - 1);
  z = std::clamp(z, 0, height - 1);
  return h[size_t(z) * size_t(width) + size_t(x)];
}

namespace {

// GLSL's definition of mix(); exact at a = 0 and a = 1, which keeps sample() == at() on grid points.
inline float mixf(float x, float y, float a) {
  return x * (1.0f - a) + y * a;
}

// clamp to [0,1] that maps NaN to 0 instead of passing it on to a float->int conversion.
inline float saturate(float v) {
  v = v > 0.0f ? v : 0.0f;
  return v < 1.0f ? v : 1.0f;
}

// Splits texel coordinate t of an axis with n samples into a base index and a fraction.
inline void texelSplit(float t, int n, int& i0, float& f) {
  i0 = n > 1 ? std::min(int(std::floor(t)), n - 2) : 0;
  f = t - float(i0);
}

}  // namespace

// shaders/common.glsl terrainHeight() must do exactly this arithmetic (same clamp, same floor,
// same mix order); the CPU copy is what collision, camera paths and error metrics read.
float Heightfield::sample(float worldX, float worldZ) const {
  const float tx = saturate(worldX / extent) * float(width - 1);
  const float tz = saturate(worldZ / extent) * float(height - 1);
  int x0, z0;
  float fx, fz;
  texelSplit(tx, width, x0, fx);
  texelSplit(tz, height, z0, fz);
  const float h00 = at(x0, z0), h10 = at(x0 + 1, z0);
  const float h01 = at(x0, z0 + 1), h11 = at(x0 + 1, z0 + 1);
  return mixf(mixf(h00, h10, fx), mixf(h01, h11, fx), fz);
}

void Heightfield::updateRange() {
  if (h.empty()) {
    minHeight = maxHeight = 0.0f;
    return;
  }
  // Bands of rows on the terrain threads (a 65537^2 terrain is 4.3 G samples): min and max are
  // exact and order-free, so the range is the same whatever the bands.
  const int rows = width > 0 && size_t(width) * size_t(height) == h.size() ? height : 1;
  const size_t perRow = h.size() / size_t(rows);
  std::vector<std::pair<float, float>> band(size_t(rows), {h[0], h[0]});
  parallelRows(
      rows,
      [&](int z0, int z1) {
        const auto [lo, hi] =
            std::minmax_element(h.begin() + ptrdiff_t(size_t(z0) * perRow), h.begin() + ptrdiff_t(size_t(z1) * perRow));
        band[size_t(z0)] = {*lo, *hi};
      },
      256);
  minHeight = band[0].first;
  maxHeight = band[0].second;
  for (const auto& [lo, hi] : band) {  // ties as minmax_element breaks them: the first min, the last max
    if (lo < minHeight) minHeight = lo;
    if (!(hi < maxHeight)) maxHeight = hi;
  }
}

namespace {

constexpr int kMinSize = 2;
constexpr int kMaxSize = 32768;         // one image: the largest maxImageDimension2D of current GPUs
constexpr int kMaxPagedSize = 262145;   // in pages ("page"): config.cpp's bound
constexpr int kOctaves = 8;             // the default ("detail": "fixed"): the finest cell is 1/192 of the extent
constexpr int kMaxOctaves = 16;         // "detail": "resolution" needs 13 at 16385^2, 14 at 32768^2
constexpr int kRidgedOctaves = 5;       // octaves 1..5; octave 0 is uplift, the rest fBm detail
constexpr float kBaseFrequency = 1.5f;  // noise cells across the whole terrain at octave 0
constexpr float kRidgeOffset = 1.0f;    // Musgrave's offset: 1 puts the crest at noise == 0
constexpr float kRidgeGain = 2.0f;      // how strongly a high octave gates the next one
constexpr float kGain = 0.5f;           // amplitude ratio between octaves (exact in binary)
constexpr float kUpliftScale = 0.5f;    // weight of the broad uplift relative to the ridges
// Each octave is rotated by ~36.87 degrees (a 3-4-5 triangle, so the entries are exact decimals
// without trig) and scaled by 2; the rotation hides the axis-aligned lattice of the noise.
constexpr float kRotC = 0.8f * 2.0f, kRotS = 0.6f * 2.0f;
// 2D gradient noise peaks at ~0.71 with these gradients; stretch it to roughly [-1, 1].
constexpr float kNoiseScale = 1.41f;

// lowbias32 (Chris Wellons): a cheap integer finaliser with good avalanche.
inline uint32_t mix32(uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

inline uint32_t hashCell(int32_t x, int32_t z, uint32_t seed) {
  return mix32(uint32_t(x) * 0x8da6b343u ^ mix32(uint32_t(z) * 0xd8163841u ^ seed));
}

inline int fastFloor(float v) {
  const int i = int(v);
  return v < float(i) ? i - 1 : i;
}

// Dot of one of 8 unit gradients (picked by the top hash bits) with the offset (dx, dz).
inline float gradDot(uint32_t hash, float dx, float dz) {
  constexpr float kD = 0.70710678f;
  static constexpr float kGrad[8][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {kD, kD}, {-kD, kD}, {kD, -kD}, {-kD, -kD}};
  const float* g = kGrad[hash >> 29];
  return g[0] * dx + g[1] * dz;
}

inline float fade(float t) {
  return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f);
}

// Perlin-style gradient noise, roughly in [-1, 1], zero on lattice points.
float gradientNoise(float x, float z, uint32_t seed) {
  const int xi = fastFloor(x), zi = fastFloor(z);
  const float fx = x - float(xi), fz = z - float(zi);
  const float n00 = gradDot(hashCell(xi, zi, seed), fx, fz);
  const float n10 = gradDot(hashCell(xi + 1, zi, seed), fx - 1.0f, fz);
  const float n01 = gradDot(hashCell(xi, zi + 1, seed), fx, fz - 1.0f);
  const float n11 = gradDot(hashCell(xi + 1, zi + 1, seed), fx - 1.0f, fz - 1.0f);
  const float u = fade(fx), v = fade(fz);
  return mixf(mixf(n00, n10, u), mixf(n01, n11, u), v) * kNoiseScale;
}

struct Octave {
  uint32_t seed;
  float offsetX, offsetZ;  // moves the zero-valued lattice points of the octaves apart
  float amplitude;
};

// Hybrid in the spirit of Musgrave: octave 0 is a smooth fBm uplift that decides where the ranges
// are (and gates the first ridge octave, so lowlands get low, soft ridges); octaves 1..5 are a
// ridged multifractal (sharp crests, each octave gated by the previous one so valleys stay
// smooth); the top octaves are fBm detail scaled by the ridges, so peaks are rough and valley
// floors calm.
float hybridMultifractal(float x, float z, const Octave* oct, int octaves) {
  float uplift = 0.0f, ridged = 0.0f, detail = 0.0f, weight = 1.0f;
  for (int i = 0; i < octaves; ++i) {
    const float n = gradientNoise(x + oct[i].offsetX, z + oct[i].offsetZ, oct[i].seed);
    if (i == 0) {
      uplift = 0.5f + 0.5f * n;
      weight = std::clamp(uplift * kRidgeGain, 0.0f, 1.0f);
    } else if (i <= kRidgedOctaves) {
      float ridge = kRidgeOffset - std::fabs(n);
      ridge *= ridge * weight;
      weight = std::clamp(ridge * kRidgeGain, 0.0f, 1.0f);
      ridged += ridge * oct[i].amplitude;
    } else {
      detail += n * oct[i].amplitude;
    }
    const float rx = kRotC * x - kRotS * z;
    z = kRotS * x + kRotC * z;
    x = rx;
  }
  // Squaring widens the valleys and sharpens the peaks (a raw ridged sum is plateau-heavy).
  return uplift * kUpliftScale + ridged * ridged + detail * ridged;
}

// The same noise several samples at a time (GCC vector extensions), every lane computing exactly
// the scalar expressions above in the same order, so the same bits: 8 lanes where the processor
// has AVX2 (chosen at run time: the static build targets baseline x86-64), else 4 (SSE2). No
// fused multiply-add is formed (FMA is not enabled, and a product rounds before its sum as above).
// Generating is the largest stage of a large terrain's load (65537^2: 86-134 s on 16-32 cores one
// sample at a time).
typedef float F4 __attribute__((vector_size(16)));
typedef int32_t I4 __attribute__((vector_size(16)));
typedef uint32_t U4 __attribute__((vector_size(16)));
typedef float F8 __attribute__((vector_size(32)));
typedef int32_t I8 __attribute__((vector_size(32)));
typedef uint32_t U8 __attribute__((vector_size(32)));
template <class F>
struct Lane;
template <>
struct Lane<F4> {
  using I = I4;
  using U = U4;
};
template <>
struct Lane<F8> {
  using I = I8;
  using U = U8;
};
#define LB_LANE inline __attribute__((always_inline))
// The 8-lane templates return 32-byte vectors; they are always inlined into the AVX2 function,
// so the note that such a return's ABI differs without AVX concerns no call that is made.
#pragma GCC diagnostic ignored "-Wpsabi"

template <class U>
LB_LANE U mixLanes(U x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

template <class F, class I = typename Lane<F>::I>
LB_LANE I floorLanes(F v) {
  const I i = __builtin_convertvector(v, I);
  return i + (v < __builtin_convertvector(i, F));  // a true lane is -1
}

template <class F, class I = typename Lane<F>::I, class U = typename Lane<F>::U>
LB_LANE U hashLanes(I x, I z, uint32_t seed) {
  return mixLanes<U>(U(x) * 0x8da6b343u ^ mixLanes<U>(U(z) * 0xd8163841u ^ seed));
}

// The gradient table of gradDot() without a lookup a lane: by a permute of the table (GCC), or
// by selects on the index bits (i < 4 an axis, bit 1: z, bit 0: negative; i >= 4 a diagonal, bit
// 0: x negative, bit 1: z negative). The same constants, so the same products.
template <class F, class U = typename Lane<F>::U>
LB_LANE F gradDotLanes(U h, F dx, F dz) {
  constexpr float kD = 0.70710678f;
  const U i = h >> 29;
  const F zero = dx * 0.0f - dx * 0.0f, one = zero + 1.0f, minusOne = zero - 1.0f, d = zero + kD, minusD = zero - kD;
#if defined(__GNUC__) && !defined(__clang__)
  if constexpr (sizeof(F) == 32) {  // GCC: the 8 entries in one vector, one permute a lane (AVX2 vpermps)
    const F x = {1, -1, 0, 0, kD, -kD, kD, -kD}, z = {0, 0, 1, -1, kD, kD, -kD, -kD};
    return __builtin_shuffle(x, i) * dx + __builtin_shuffle(z, i) * dz;
  }
#endif
  const auto b0 = (i & 1u) != 0u, b1 = (i & 2u) != 0u, b2 = (i & 4u) != 0u;
  const F axis = b0 ? minusOne : one;
  const F g0 = b2 ? (b0 ? minusD : d) : (b1 ? zero : axis);
  const F g1 = b2 ? (b1 ? minusD : d) : (b1 ? axis : zero);
  return g0 * dx + g1 * dz;
}

template <class F>
LB_LANE F fadeLanes(F t) {
  return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f);
}

template <class F>
LB_LANE F mixLanesF(F a, F b, F t) {
  return a * (1.0f - t) + b * t;
}

template <class F, class I = typename Lane<F>::I>
LB_LANE F noiseLanes(F x, F z, uint32_t seed) {
  const I xi = floorLanes<F>(x), zi = floorLanes<F>(z);
  const F fx = x - __builtin_convertvector(xi, F), fz = z - __builtin_convertvector(zi, F);
  const F n00 = gradDotLanes<F>(hashLanes<F>(xi, zi, seed), fx, fz);
  const F n10 = gradDotLanes<F>(hashLanes<F>(xi + 1, zi, seed), fx - 1.0f, fz);
  const F n01 = gradDotLanes<F>(hashLanes<F>(xi, zi + 1, seed), fx, fz - 1.0f);
  const F n11 = gradDotLanes<F>(hashLanes<F>(xi + 1, zi + 1, seed), fx - 1.0f, fz - 1.0f);
  const F u = fadeLanes(fx), v = fadeLanes(fz);
  return mixLanesF(mixLanesF(n00, n10, u), mixLanesF(n01, n11, u), v) * kNoiseScale;
}

template <class F, class U = typename Lane<F>::U>
LB_LANE F clamp01(F v) {  // std::clamp(v, 0, 1): lo if v < lo, else hi if hi < v, else v
  const F zero = v * 0.0f - v * 0.0f, one = zero + 1.0f;  // every lane 0 and 1 (v finite)
  v = v < zero ? zero : v;
  return one < v ? one : v;
}

template <class F, class U = typename Lane<F>::U>
LB_LANE F multifractalLanes(F x, F z, const Octave* oct, int octaves) {
  F uplift = x * 0.0f, ridged = uplift, detail = uplift, weight = uplift + 1.0f;
  for (int i = 0; i < octaves; ++i) {
    const F n = noiseLanes<F>(x + oct[i].offsetX, z + oct[i].offsetZ, oct[i].seed);
    if (i == 0) {
      uplift = 0.5f + 0.5f * n;
      weight = clamp01<F>(uplift * kRidgeGain);
    } else if (i <= kRidgedOctaves) {
      F ridge = kRidgeOffset - F(U(n) & 0x7fffffffu);
      ridge *= ridge * weight;
      weight = clamp01<F>(ridge * kRidgeGain);
      ridged += ridge * oct[i].amplitude;
    } else {
      detail += n * oct[i].amplitude;
    }
    const F rx = kRotC * x - kRotS * z;
    z = kRotS * x + kRotC * z;
    x = rx;
  }
  return uplift * kUpliftScale + ridged * ridged + detail * ridged;
}

// Samples [0, k) of a row of `size` where k is the largest multiple of the lane count; returns k.
template <class F>
LB_LANE int rowLanes(float* row, int size, float zs, float step, const Octave* oct, int octaves) {
  constexpr int n = int(sizeof(F) / sizeof(float));
  int x = 0;
  for (; x + n <= size; x += n) {
    F xs, zv;
    for (int k = 0; k < n; ++k) xs[k] = float(x + k) * step, zv[k] = zs;
    const F v = multifractalLanes<F>(xs, zv, oct, octaves);
    for (int k = 0; k < n; ++k) row[x + k] = v[k];
  }
  return x;
}

__attribute__((target("avx2"))) int rowLanesAvx2(float* row, int size, float zs, float step, const Octave* oct,
                                                 int octaves) {
  return rowLanes<F8>(row, size, zs, step, oct, octaves);
}

int rowLanesBase(float* row, int size, float zs, float step, const Octave* oct, int octaves) {
  return rowLanes<F4>(row, size, zs, step, oct, octaves);
}

void requireFinite(float v, const char* what, bool allowZero) {
  if (!(std::isfinite(v) && (v > 0.0f || (allowZero && v == 0.0f))))
    throw InputError("terrain: " + std::string(what) + " " + std::to_string(v) + " must be a finite number " +
                     (allowZero ? ">= 0" : "> 0"));
}

}  // namespace

Heightfield makeProcedural(const TerrainSpec& spec, int lanes) {
  const int maxSize = spec.page > 0 ? kMaxPagedSize : kMaxSize;
  if (spec.size < kMinSize || spec.size > maxSize)
    throw InputError("terrain: procedural size " + std::to_string(spec.size) + " is outside [" +
                     std::to_string(kMinSize) + ", " + std::to_string(maxSize) + "]" +
                     (spec.page > 0 ? "" : " (a terrain in pages, \"page\", may be larger)"));
  requireFinite(spec.extent, "extent", false);
  requireFinite(spec.heightScale, "heightScale", true);  // 0 gives a flat plane, a valid baseline
  if (spec.heightScale > kMaxAbsHeight)
    throw InputError("terrain: procedural heightScale " + std::to_string(spec.heightScale) +
                     " is above the largest height accepted, 1e5 (see kMaxAbsHeight)");

  // Octave i has kBaseFrequency * 2^i noise cells across the terrain. "detail": "resolution" adds
  // fBm octaves while a cell still spans >= 2 sample spacings (the finest relief the samples can
  // hold), never fewer than the default 8, whose values it leaves unchanged (octaves 0..7 are the same).
  int octaves = kOctaves;
  if (spec.detailToSpacing)
    while (octaves < kMaxOctaves && float(spec.size - 1) / (kBaseFrequency * float(1 << octaves)) >= 2.0f) ++octaves;
  Octave oct[kMaxOctaves];
  float amplitude = 1.0f;
  for (int i = 0; i < octaves; ++i) {
    const uint32_t s = mix32(spec.seed * 0x9e3779b9u + uint32_t(i) * 0x85ebca6bu + 0x165667b1u);
    const uint32_t a = mix32(s ^ 0x27d4eb2fu), b = mix32(s ^ 0x61c88647u);
    // 24-bit fractions -> offsets in [0, 256): exact in float, far from the lattice of octave 0.
    oct[i] = {s, float(a >> 8) * (256.0f / 16777216.0f), float(b >> 8) * (256.0f / 16777216.0f), amplitude};
    if (i > 0) amplitude *= kGain;
  }

  Heightfield hf;
  hf.width = hf.height = spec.size;
  hf.extent = spec.extent;
  hf.h.resize(size_t(spec.size) * size_t(spec.size));
  const float step = kBaseFrequency / float(spec.size - 1);
  auto laneRow = lanes >= 8 && __builtin_cpu_supports("avx2") ? rowLanesAvx2 : lanes >= 4 ? rowLanesBase : nullptr;
  auto fillRows = [&](int z0, int z1) {
    for (int z = z0; z < z1; ++z) {
      float* row = &hf.h[size_t(z) * size_t(spec.size)];
      int x = 0;
      if (laneRow) x = laneRow(row, spec.size, float(z) * step, step, oct, octaves);
      for (; x < spec.size; ++x) row[x] = hybridMultifractal(float(x) * step, float(z) * step, oct, octaves);
    }
  };
  // Samples are independent, so splitting rows across threads cannot change a single bit; it only
  // matters for the large sizes (16385^2 takes ~30 s on one core).
  parallelRows(spec.size, fillRows, 256);

  hf.updateRange();
  const float span = hf.maxHeight - hf.minHeight;
  const float scale = span > 0.0f ? spec.heightScale / span : 0.0f;
  const float lo = hf.minHeight;
  // Clamp because (max - min) * (heightScale / span) can round a hair above heightScale.
  parallelRows(
      spec.size,
      [&](int z0, int z1) {
        for (size_t i = size_t(z0) * size_t(spec.size); i < size_t(z1) * size_t(spec.size); ++i)
          hf.h[i] = std::min((hf.h[i] - lo) * scale, spec.heightScale);
      },
      256);
  hf.updateRange();
  return hf;
}

Heightfield makeHeightfield(const TerrainSpec& spec) {
  auto placed = [&spec](Heightfield hf) {
    hf.originX = spec.originX;
    hf.originZ = spec.originZ;
    hf.page = spec.page;
    return hf;
  };
  if (spec.type == "procedural") return placed(makeProcedural(spec));
  if (isGeneratedTerrain(spec.type)) {
    Heightfield hf = makeGeneratedTerrain(spec);
    hf.source = TerrainSource{};  // "voids" goes through a temporary .hgt file: still a generated terrain
    return placed(std::move(hf));
  }
  if (spec.type == "hgt" || spec.type == "png16" || spec.type == "r16" || spec.type == "r32f" || spec.type == "gdal")
    return placed(loadHeightfield(spec));
  throw InputError("terrain: unknown type '" + spec.type +
                   "' (valid types: procedural, hgt, png16, r16, r32f, gdal, spikes, cliff, flat, voids, canyon)");
}

uint64_t Heightfield::heightHash() const {
  std::vector<uint64_t> rowHash(size_t(std::max(height, 0)));
  parallelRows(height, [&](int z0, int z1) {
    for (int z = z0; z < z1; ++z) {
      uint64_t hash = 1469598103934665603ull;
      for (size_t i = size_t(z) * size_t(width); i < size_t(z + 1) * size_t(width); ++i) {
        uint32_t bits;
        std::memcpy(&bits, &h[i], 4);
        hash = (hash ^ bits) * 1099511628211ull;
      }
      rowHash[size_t(z)] = hash;
    }
  });
  uint64_t hash = 1469598103934665603ull;
  for (uint64_t r : rowHash) hash = (hash ^ r) * 1099511628211ull;
  return hash;
}

}  // namespace lb
