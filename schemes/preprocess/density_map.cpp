#include "schemes/preprocess/density_map.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdlib>
#include <vector>

#include "terrain/heightfield.h"
#include "terrain/parallel_rows.h"

namespace lb {

namespace {

constexpr float kAxisWeight = 0.293f;      // horizontal and vertical variation
constexpr float kDiagonalWeight = 0.207f;  // both diagonal variations

// |(next - centre) - (centre - previous)|, written as the seed writes it.
inline float variation(float previous, float centre, float next) {
  return std::fabs((next - centre) - (centre - previous));
}

// Round-half-away-from-zero of num / den for den > 0.
inline int roundDiv(int num, int den) {
  int q = (2 * std::abs(num) + den) / (2 * den);
  return num < 0 ? -q : q;
}

// Densities of samples x0 .. x0 + count - 1 of one row from the normalised rows above, at and below
// it, whose element 0 is column `first` (only columns clamp(x, 1, w - 2) + {-1, 0, 1} are read).
void densityFromRows(const float* up, const float* mid, const float* down, int first, int w, int x0, int count,
                     float threshold, float scale, float* out) {
  for (int x = x0; x < x0 + count; ++x) {
    const int cx = std::clamp(x, 1, w - 2) - first;  // border: nearest interior
    const float c = mid[cx];
    const float horizontal = variation(mid[cx - 1], c, mid[cx + 1]);
    const float vertical = variation(up[cx], c, down[cx]);
    const float firstDiagonal = variation(down[cx - 1], c, up[cx + 1]);
    const float secondDiagonal = variation(up[cx - 1], c, down[cx + 1]);
    float density = 0.0f;
    if (horizontal >= threshold) density += kAxisWeight * horizontal;
    if (vertical >= threshold) density += kAxisWeight * vertical;
    if (firstDiagonal >= threshold) density += kDiagonalWeight * firstDiagonal;
    if (secondDiagonal >= threshold) density += kDiagonalWeight * secondDiagonal;
    density *= scale;
    out[x - x0] = std::max(std::min(density, 1.0f), kMinDensity);
  }
}

}  // namespace

std::vector<float> densityMap(const Heightfield& hf, float threshold, float scale) {
  const int w = hf.width, h = hf.height;
  std::vector<float> out(size_t(w) * size_t(h), kMinDensity);
  if (w < 3 || h < 3) return out;  // no interior sample has all eight neighbours
  const float range = hf.maxHeight - hf.minHeight;
  auto normalised = [&](float v) { return range > 0 ? (v - hf.minHeight) / range : 0.0f; };
  // Rows are independent: bands on every hardware thread give the same map as one thread. Each
  // band normalises a row once into a 3-row ring (rows cz - 1, cz, cz + 1) instead of every
  // sample 9 times: the same function of the same sample, so the same floats.
  parallelRows(h, [&](int z0, int z1) {
    std::vector<float> ring(size_t(w) * 3);
    int tag[3] = {-1, -1, -1};
    auto row = [&](int r) {
      float* dst = &ring[size_t(r % 3) * size_t(w)];
      if (tag[r % 3] != r) {
        const float* src = &hf.h[size_t(r) * size_t(w)];
        for (int x = 0; x < w; ++x) dst[x] = normalised(src[x]);
        tag[r % 3] = r;
      }
      return static_cast<const float*>(dst);
    };
    for (int z = z0; z < z1; ++z) {
      const int cz = std::clamp(z, 1, h - 2);  // border: nearest interior
      densityFromRows(row(cz - 1), row(cz), row(cz + 1), 0, w, 0, w, threshold, scale, &out[size_t(z) * size_t(w)]);
    }
  });
  return out;
}

void densityRow(const Heightfield& hf, float threshold, float scale, int z, int x0, int count, float* out) {
  const int w = hf.width, h = hf.height;
  if (w < 3 || h < 3) {
    std::fill(out, out + count, kMinDensity);
    return;
  }
  const float range = hf.maxHeight - hf.minHeight;
  // The columns the span reads, normalised as densityMap does (the same floats).
  const int lo = std::clamp(x0, 1, w - 2) - 1, hi = std::clamp(x0 + count - 1, 1, w - 2) + 1;
  const int n = hi - lo + 1;
  std::vector<float> rows(size_t(n) * 3);
  const int cz = std::clamp(z, 1, h - 2);
  for (int k = 0; k < 3; ++k) {
    const float* src = &hf.h[size_t(cz - 1 + k) * size_t(w) + size_t(lo)];
    for (int i = 0; i < n; ++i)
      rows[size_t(k) * size_t(n) + size_t(i)] = range > 0 ? (src[i] - hf.minHeight) / range : 0.0f;
  }
  densityFromRows(rows.data(), rows.data() + n, rows.data() + 2 * n, lo, w, x0, count, threshold, scale, out);
}

int gridTexel(int i, int n, int size) {
  assert(i >= 0 && n > 0 && size > 0);
  return (2 * i * (size - 1) + n) / (2 * n);
}

float maxDensityAlongEdge(const std::vector<float>& map, int w, glm::ivec2 a, glm::ivec2 b) {
  if (b.x < a.x || (b.x == a.x && b.y < a.y)) std::swap(a, b);
  const glm::ivec2 d = b - a;
  const int steps = std::max(std::abs(d.x), std::abs(d.y));
  float best = 0.0f;
  for (int k = 0; k <= steps; ++k) {
    glm::ivec2 t = steps == 0 ? a : a + glm::ivec2(roundDiv(k * d.x, steps), roundDiv(k * d.y, steps));
    best = std::max(best, map[size_t(t.y) * size_t(w) + size_t(t.x)]);
  }
  return best;
}

}  // namespace lb
