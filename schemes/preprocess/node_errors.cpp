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

namespace {

// Per level, the largest deviation of the cells of every block of n x n cells (blocks in rows of
// `cols / n`, rounded up), levels [p0, p1). The cell scan does not depend on n, so a table for
// small blocks gives every multiple of it by a max over its blocks.
void scanLevels(const Heightfield& hf, double cellsX, double cellsZ, double q, int n, int p0, int p1,
                std::vector<std::vector<float>>& dev, std::vector<int>& bx) {
  using glm::dvec2;
  dev.resize(size_t(p1));
  bx.resize(size_t(p1));
  for (int p = p0; p < p1; ++p) {
    const double s = std::ldexp(1.0, p);
    const int rows = int(std::ceil(cellsZ / s)), cols = int(std::ceil(cellsX / s));
    const int blockCols = (cols + n - 1) / n, blockRows = (rows + n - 1) / n;
    // Per cell row and block column, so that every level (the coarse ones have few block rows)
    // spreads over the threads.
    std::vector<float> rowMax(size_t(rows) * size_t(blockCols), 0.0f);
    // The top levels have fewer cell rows than threads, and each of their cells covers a large
    // part of the terrain: there the cells go one after the other and each triangle's samples
    // spread over the threads instead (the same bits either way).
    const bool fewRows = rows < terrainThreads();
    auto scanRows = [&](int r0, int r1) {
      for (int r = r0; r < r1; ++r) {
        const double z0 = r * s / q, z1 = std::min((r + 1) * s, cellsZ) / q;
        for (int c = 0; c < cols; ++c) {
          const double x0 = c * s / q, x1 = std::min((c + 1) * s, cellsX) / q;
          const dvec2 v00(x0, z0), v10(x1, z0), v11(x1, z1), v01(x0, z1);
          const double d =
              std::max(triangleDeviation(hf, v00, v10, v11, fewRows), triangleDeviation(hf, v00, v11, v01, fewRows));
          float& m = rowMax[size_t(r) * size_t(blockCols) + size_t(c / n)];
          m = std::max(m, float(d));
        }
      }
    };
    if (fewRows)
      scanRows(0, rows);
    else
      parallelRows(rows, scanRows, std::max(1, 4096 / std::max(1, cols)));
    std::vector<float>& out = dev[size_t(p)];
    out.assign(size_t(blockCols) * size_t(blockRows), 0.0f);
    for (int r = 0; r < rows; ++r)
      for (int i = 0; i < blockCols; ++i) {
        float& d = out[size_t(r / n) * size_t(blockCols) + size_t(i)];
        d = std::max(d, rowMax[size_t(r) * size_t(blockCols) + size_t(i)]);
      }
    bx[size_t(p)] = blockCols;
  }
}

// Blocks of this many cells a side: every node size that is a multiple of it (cdlod-sse's tuning
// tries 16 and 64) is read from one scan of the terrain per lattice, not one scan per node size.
constexpr int kUnitCells = 16;

struct UnitErrors {
  std::vector<std::vector<float>> dev;  // per level, per block of kUnitCells^2 cells
  std::vector<int> bx;                  // blocks per row, per level
};

// The unit table of (heights, lattice) with at least `levels` levels, kept for the last few.
std::shared_ptr<const UnitErrors> unitErrors(const Heightfield& hf, const MinMaxPyramid& pyr, double q, int levels) {
  struct Entry {
    int width, height;
    double q, cellsX, cellsZ;
    uint64_t hash;
    std::shared_ptr<const UnitErrors> errors;
  };
  static std::mutex mutex;
  static std::list<Entry> cache;
  const uint64_t hash = hf.heightHash();
  std::lock_guard<std::mutex> lock(mutex);
  for (auto it = cache.begin(); it != cache.end(); ++it)
    if (it->width == hf.width && it->height == hf.height && it->q == q && it->cellsX == pyr.cellsX &&
        it->cellsZ == pyr.cellsZ && it->hash == hash) {
      if (int(it->errors->dev.size()) < levels) {  // a smaller node size climbs higher: add its levels
        auto more = std::make_shared<UnitErrors>(*it->errors);
        scanLevels(hf, pyr.cellsX, pyr.cellsZ, q, kUnitCells, int(more->dev.size()), levels, more->dev, more->bx);
        it->errors = more;
      }
      cache.splice(cache.begin(), cache, it);
      return cache.front().errors;
    }
  auto made = std::make_shared<UnitErrors>();
  scanLevels(hf, pyr.cellsX, pyr.cellsZ, q, kUnitCells, 0, levels, made->dev, made->bx);
  cache.push_front({hf.width, hf.height, q, pyr.cellsX, pyr.cellsZ, hash, made});
  if (cache.size() > 4) cache.pop_back();
  return cache.front().errors;
}

}  // namespace

NodeErrors computeNodeErrors(const Heightfield& hf, const MinMaxPyramid& pyr, double q) {
  NodeErrors out;
  const int levels = pyr.top() + 1;
  out.dev.resize(size_t(levels));
  const int n = pyr.base;
  if (n % kUnitCells != 0) {  // no unit table serves it: scan for this node size alone
    std::vector<int> bx;
    scanLevels(hf, pyr.cellsX, pyr.cellsZ, q, n, 0, levels, out.dev, bx);
  } else {
    const std::shared_ptr<const UnitErrors> unit = unitErrors(hf, pyr, q, levels);
    const int k = n / kUnitCells;  // unit blocks a node side
    for (int p = 0; p < levels; ++p) {
      const std::vector<float>& u = unit->dev[size_t(p)];
      const int ux = unit->bx[size_t(p)], uz = ux > 0 ? int(u.size()) / ux : 0;
      std::vector<float> d(size_t((ux + k - 1) / k) * size_t((uz + k - 1) / k), 0.0f);
      const int nodeCols = (ux + k - 1) / k;
      for (int j = 0; j < uz; ++j)
        for (int i = 0; i < ux; ++i) {
          float& m = d[size_t(j / k) * size_t(nodeCols) + size_t(i / k)];
          m = std::max(m, u[size_t(j) * size_t(ux) + size_t(i)]);
        }
      out.dev[size_t(p)] = std::move(d);
    }
  }
  // Into the pyramid's node layout (its rows may hold more nodes than the lattice reaches: 0 there).
  for (int p = 0; p < levels; ++p) {
    const double s = std::ldexp(1.0, p);
    const int cols = int(std::ceil(pyr.cellsX / s)), rows = int(std::ceil(pyr.cellsZ / s));
    const int nodeCols = (cols + n - 1) / n, nodeRows = (rows + n - 1) / n;
    std::vector<float> laid(size_t(pyr.nx[size_t(p)]) * size_t(pyr.nz[size_t(p)]), 0.0f);
    for (int j = 0; j < nodeRows; ++j)
      for (int i = 0; i < nodeCols; ++i)
        laid[pyr.index(p, i, j)] = out.dev[size_t(p)][size_t(j) * size_t(nodeCols) + size_t(i)];
    out.dev[size_t(p)] = std::move(laid);
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
