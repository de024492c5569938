#include "schemes/preprocess/min_max_pyramid.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "terrain/heightfield.h"
#include "terrain/parallel_rows.h"

namespace lb {

namespace {

// Level p's bounds from the samples: every sample the bilinear surface over each block touches
// (lattice / q in texels; q is a power of two, so the divisions are exact).
void scanLevel(MinMaxPyramid& pyr, const Heightfield& hf, int p) {
  const double s = pyr.size(p), q = pyr.q;
  const int nx = pyr.nx[size_t(p)], nz = pyr.nz[size_t(p)];
  std::vector<glm::vec2>& out = pyr.bounds[size_t(p)];
  out.assign(size_t(nx) * size_t(nz), glm::vec2(0));
  auto texelRange = [&](int i, double cells, int samples, int& t0, int& t1) {
    const double lo = double(i) * s, hi = std::min(double(i + 1) * s, cells);
    t0 = std::clamp(int(std::floor(lo / q)), 0, samples - 1);
    t1 = std::clamp(int(std::ceil(hi / q)), 0, samples - 1);
  };
  parallelRows(
      nz,
      [&](int j0, int j1) {
        for (int j = j0; j < j1; ++j) {
          int z0, z1;
          texelRange(j, pyr.cellsZ, hf.height, z0, z1);
          for (int i = 0; i < nx; ++i) {
            int x0, x1;
            texelRange(i, pyr.cellsX, hf.width, x0, x1);
            float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
            for (int z = z0; z <= z1; ++z) {
              const float* row = &hf.h[size_t(z) * size_t(hf.width)];
              for (int x = x0; x <= x1; ++x) {
                lo = std::min(lo, row[x]);
                hi = std::max(hi, row[x]);
              }
            }
            out[size_t(j) * size_t(nx) + size_t(i)] = {lo, hi};
          }
        }
      },
      std::max(1, 4096 / std::max(1, nx)));
}

// Levels from + 1 to to, each from its children: min and max are exact in any order.
void combineUp(MinMaxPyramid& pyr, int from, int to) {
  for (int p = from + 1; p <= to; ++p) {
    pyr.bounds[size_t(p)].assign(size_t(pyr.nx[size_t(p)]) * size_t(pyr.nz[size_t(p)]),
                                 glm::vec2(std::numeric_limits<float>::max(), std::numeric_limits<float>::lowest()));
    for (int j = 0; j < pyr.nz[size_t(p - 1)]; ++j)
      for (int i = 0; i < pyr.nx[size_t(p - 1)]; ++i) {
        glm::vec2 c = pyr.bounds[size_t(p - 1)][pyr.index(p - 1, i, j)];
        glm::vec2& b = pyr.bounds[size_t(p)][pyr.index(p, i / 2, j / 2)];
        b = {std::min(b.x, c.x), std::max(b.y, c.y)};
      }
  }
}

}  // namespace

MinMaxPyramid buildMinMaxPyramid(const Heightfield& hf, double q, int base, int minTopCells, glm::dvec2 cell,
                                 int firstLevel) {
  MinMaxPyramid pyr;
  pyr.cellsX = double(hf.width - 1) * q;
  pyr.cellsZ = double(hf.height - 1) * q;
  pyr.cell = cell;
  pyr.q = q;
  pyr.base = base;
  for (int p = 0;; ++p) {
    const double s = pyr.size(p);
    pyr.nx.push_back(int(std::ceil(pyr.cellsX / s)));
    pyr.nz.push_back(int(std::ceil(pyr.cellsZ / s)));
    if (pyr.nx.back() == 1 && pyr.nz.back() == 1 && s >= minTopCells) break;
  }
  pyr.bounds.resize(pyr.nx.size());
  pyr.built = std::clamp(firstLevel, 0, pyr.top());
  scanLevel(pyr, hf, pyr.built);
  combineUp(pyr, pyr.built, pyr.top());
  return pyr;
}

void extendMinMaxPyramid(MinMaxPyramid& pyr, const Heightfield& hf, int level) {
  level = std::max(level, 0);
  if (level >= pyr.built) return;
  scanLevel(pyr, hf, level);
  combineUp(pyr, level, pyr.built - 1);
  pyr.built = level;
}

}  // namespace lb
