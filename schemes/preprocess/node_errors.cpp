#include "schemes/preprocess/node_errors.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <list>
#include <mutex>

#include "schemes/preprocess/tess_deviation.h"
#include "terrain/heightfield.h"
#include "terrain/parallel_rows.h"

namespace lb {

NodeErrors computeNodeErrors(const Heightfield& hf, const MinMaxPyramid& pyr, double q) {
  using glm::dvec2;
  NodeErrors out;
  out.dev.resize(pyr.nx.size());
  const int n = pyr.base;
  for (int p = 0; p <= pyr.top(); ++p) {
    const double s = std::ldexp(1.0, p);
    const int rows = int(std::ceil(pyr.cellsZ / s)), cols = int(std::ceil(pyr.cellsX / s));
    const int nodeCols = pyr.nx[size_t(p)];
    // Per cell row and node column, so that every level (the coarse ones have few node rows)
    // spreads over the threads.
    std::vector<float> rowMax(size_t(rows) * size_t(nodeCols), 0.0f);
    parallelRows(
        rows,
        [&](int r0, int r1) {
          for (int r = r0; r < r1; ++r) {
            const double z0 = r * s / q, z1 = std::min((r + 1) * s, pyr.cellsZ) / q;
            for (int c = 0; c < cols; ++c) {
              const double x0 = c * s / q, x1 = std::min((c + 1) * s, pyr.cellsX) / q;
              const dvec2 v00(x0, z0), v10(x1, z0), v11(x1, z1), v01(x0, z1);
              const double d = std::max(triangleDeviation(hf, v00, v10, v11), triangleDeviation(hf, v00, v11, v01));
              float& m = rowMax[size_t(r) * size_t(nodeCols) + size_t(c / n)];
              m = std::max(m, float(d));
            }
          }
        },
        std::max(1, 4096 / std::max(1, cols)));
    out.dev[size_t(p)].assign(size_t(nodeCols) * size_t(pyr.nz[size_t(p)]), 0.0f);
    for (int r = 0; r < rows; ++r)
      for (int i = 0; i < nodeCols; ++i) {
        float& d = out.dev[size_t(p)][pyr.index(p, i, r / n)];
        d = std::max(d, rowMax[size_t(r) * size_t(nodeCols) + size_t(i)]);
      }
  }
  return out;
}

std::shared_ptr<const NodeErrors> cachedNodeErrors(const Heightfield& hf, const MinMaxPyramid& pyr, double q) {
  struct Entry {
    int width, height, base;
    double q;
    uint64_t hash;
    std::shared_ptr<const NodeErrors> errors;
  };
  static std::mutex mutex;
  static std::list<Entry> cache;
  const uint64_t hash = hf.heightHash();
  std::lock_guard<std::mutex> lock(mutex);
  for (auto it = cache.begin(); it != cache.end(); ++it)
    if (it->width == hf.width && it->height == hf.height && it->base == pyr.base && it->q == q && it->hash == hash) {
      cache.splice(cache.begin(), cache, it);
      return cache.front().errors;
    }
  cache.push_front(
      {hf.width, hf.height, pyr.base, q, hash, std::make_shared<const NodeErrors>(computeNodeErrors(hf, pyr, q))});
  if (cache.size() > 4) cache.pop_back();
  return cache.front().errors;
}

}  // namespace lb
