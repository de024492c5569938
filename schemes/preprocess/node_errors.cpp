#include "schemes/preprocess/node_errors.h"

#include <emmintrin.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <list>
#include <mutex>

#include "schemes/preprocess/tess_deviation.h"
#include "terrain/heightfield.h"
#include "terrain/parallel_rows.h"

namespace lb {

namespace {

// An upper bound on max(triangleDeviation) of the cell's two triangles, for a cell whose corners
// are samples (columns ix0..ix1, rows iz0..iz1 of the heightfield).
// Let L be the bilinear interpolant of the four corner heights over the cell. Each triangle's
// plane P equals L on the triangle's two axis-aligned edges, and L - P = -t u (1 - v) over the
// triangle (t the corner twist h00 - h10 - h01 + h11, u and v in [0, 1] along the axes with
// u (1 - v) <= 1/4), so |L - P| <= |t| / 4. On every texel cell inside, both B and L are bilinear,
// so |B - L| is largest at a sample: |B - P| <= max over samples |h - L| + |t| / 4. The slack
// covers the rounding of both this bound and the exact computation.
double sampleCellBound(const Heightfield& hf, int ix0, int iz0, int ix1, int iz1) {
  const size_t w = size_t(hf.width);
  const double h00 = hf.h[size_t(iz0) * w + size_t(ix0)], h10 = hf.h[size_t(iz0) * w + size_t(ix1)];
  const double h01 = hf.h[size_t(iz1) * w + size_t(ix0)], h11 = hf.h[size_t(iz1) * w + size_t(ix1)];
  const double a = h10 - h00, b = h01 - h00, t = h00 - h10 - h01 + h11;
  const double slack = 1e-9 * (std::abs(h00) + std::abs(h10) + std::abs(h01) + std::abs(h11) + 1.0);
  // One texel: B is L itself, no sample inside.
  if (ix1 - ix0 == 1 && iz1 - iz0 == 1) return 0.25 * std::abs(t) * (1.0 + 1e-9) + slack;
  const double sx = 1.0 / (ix1 - ix0), sz = 1.0 / (iz1 - iz0);
  // Two samples at a time (SSE2, every x86-64): the bound needs no exact rounding, its slack covers it.
  const __m128d absMask = _mm_castsi128_pd(_mm_set1_epi64x(0x7fffffffffffffffll)), two = _mm_set1_pd(2.0);
  __m128d acc = _mm_setzero_pd();
  const int last = ix1 - ix0;
  for (int z = iz0; z <= iz1; ++z) {
    const double v = (z - iz0) * sz;
    const double base = h00 + b * v, slope = (a + t * v) * sx;  // L along the row: base + slope (x - x0)
    const float* row = &hf.h[size_t(z) * w + size_t(ix0)];
    const __m128d vb = _mm_set1_pd(base), vs = _mm_set1_pd(slope);
    __m128d iv = _mm_set_pd(1.0, 0.0);
    int i = 0;
    for (; i + 1 <= last; i += 2) {
      const __m128d h = _mm_cvtps_pd(_mm_castsi128_ps(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(row + i))));
      acc = _mm_max_pd(acc, _mm_and_pd(_mm_sub_pd(h, _mm_add_pd(vb, _mm_mul_pd(vs, iv))), absMask));
      iv = _mm_add_pd(iv, two);
    }
    if (i == last) acc = _mm_max_pd(acc, _mm_set_sd(std::abs(double(row[i]) - (base + slope * i))));
  }
  const double r = std::max(_mm_cvtsd_f64(acc), _mm_cvtsd_f64(_mm_unpackhi_pd(acc, acc)));
  const double bound = r + 0.25 * std::abs(t);
  return bound * (1.0 + 1e-9) + slack;
}

// The bound of a cell given in texel coordinates: +infinity for a cell whose corners are not samples.
double cellBound(const Heightfield& hf, double x0, double z0, double x1, double z1) {
  if (x0 != std::floor(x0) || x1 != std::floor(x1) || z0 != std::floor(z0) || z1 != std::floor(z1) ||
      x1 > hf.width - 1 || z1 > hf.height - 1 || x1 <= x0 || z1 <= z0 || x0 < 0 || z0 < 0)
    return INFINITY;
  return sampleCellBound(hf, int(x0), int(z0), int(x1), int(z1));
}

// The exact deviation of one cell: the larger of its two triangles'.
double cellDeviation(const Heightfield& hf, double x0, double z0, double x1, double z1, bool rowsInParallel) {
  using glm::dvec2;
  const dvec2 v00(x0, z0), v10(x1, z0), v11(x1, z1), v01(x0, z1);
  return std::max(triangleDeviation(hf, v00, v10, v11, rowsInParallel),
                  triangleDeviation(hf, v00, v11, v01, rowsInParallel));
}

// Per level, the largest deviation of the cells of every block of n x n cells (blocks in rows of
// `cols / n`, rounded up), levels [p0, p1). The cell scan does not depend on n, so a table for
// small blocks gives every multiple of it by a max over its blocks.
// A block's value is a maximum, so a cell whose upper bound (cellBound) is below the largest
// exact deviation found so far in its block cannot change it: the cell of the largest bound goes
// first, then only the cells whose bound reaches the largest deviation found so far. The same bits as computing every
// cell, at a fraction of the cost (the exact edge walk is most of it).
void scanLevels(const Heightfield& hf, double cellsX, double cellsZ, double q, int n, int p0, int p1,
                std::vector<std::vector<float>>& dev, std::vector<int>& bx) {
  dev.resize(size_t(p1));
  bx.resize(size_t(p1));
  const int threads = terrainThreads();
  for (int p = p0; p < p1; ++p) {
    const double s = std::ldexp(1.0, p);
    const int rows = int(std::ceil(cellsZ / s)), cols = int(std::ceil(cellsX / s));
    const int blockCols = (cols + n - 1) / n, blockRows = (rows + n - 1) / n;
    auto cellBox = [&](int r, int c, double& x0, double& z0, double& x1, double& z1) {
      z0 = r * s / q, z1 = std::min((r + 1) * s, cellsZ) / q;
      x0 = c * s / q, x1 = std::min((c + 1) * s, cellsX) / q;
    };
    std::vector<float>& out = dev[size_t(p)];
    out.assign(size_t(blockCols) * size_t(blockRows), 0.0f);
    bx[size_t(p)] = blockCols;
    // The top levels have fewer cell rows than threads, and each of their cells covers a large
    // part of the terrain: there the cells go one after the other and each triangle's samples
    // spread over the threads instead (the same bits either way).
    if (rows < threads) {
      for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) {
          double x0, z0, x1, z1;
          cellBox(r, c, x0, z0, x1, z1);
          float& m = out[size_t(r / n) * size_t(blockCols) + size_t(c / n)];
          m = std::max(m, float(cellDeviation(hf, x0, z0, x1, z1, true)));
        }
      continue;
    }
    // Bands of g cell rows inside one block row (g divides n), as many as keep the threads busy;
    // each band's maximum per block column, then the blocks' over their bands.
    int g = 1;
    for (int d = n; d >= 1; --d)
      if (n % d == 0 && (rows + d - 1) / d >= 2 * threads) {
        g = d;
        break;
      }
    const int bands = (rows + g - 1) / g;
    // Where q is a power of two and a cell a whole number of samples, the cells' corners are the
    // integers cellBox gives exactly (c s / q = c step, the last clamped to the terrain's last
    // sample): their bounds skip the conversions. step 0: cellBound checks each cell.
    int step = 0, lastX = 0, lastZ = 0;
    if (q == std::ldexp(1.0, std::ilogb(q)) && s / q == std::floor(s / q) && s / q < 1 << 30 &&
        cellsX / q == std::floor(cellsX / q) && cellsZ / q == std::floor(cellsZ / q) && cellsX / q <= hf.width - 1 &&
        cellsZ / q <= hf.height - 1) {
      step = int(s / q);
      lastX = int(cellsX / q);
      lastZ = int(cellsZ / q);
    }
    std::vector<float> bandMax(size_t(bands) * size_t(blockCols), 0.0f);
    // Bands are handed out one at a time (pruning makes their costs uneven); each writes only
    // its own entries, so the order they are taken in changes nothing.
    std::atomic<int> next{0};
    const int workers = int(std::clamp<int64_t>(int64_t(rows) * cols / 4096, 1, threads));  // small terrains: one
    parallelRows(
        workers,
        [&](int, int) {
          std::vector<double> bound;
          for (int band; (band = next.fetch_add(1)) < bands;) {
            const int r0 = band * g, r1 = std::min(rows, r0 + g);
            for (int i = 0; i < blockCols; ++i) {
              const int c0 = i * n, c1 = std::min(cols, c0 + n), w = c1 - c0;
              bound.assign(size_t((r1 - r0) * w), 0.0);
              size_t top = 0;
              for (int r = r0; r < r1; ++r)
                for (int c = c0; c < c1; ++c) {
                  const size_t k = size_t((r - r0) * w + (c - c0));
                  if (step > 0) {
                    bound[k] = sampleCellBound(hf, c * step, r * step, std::min((c + 1) * step, lastX),
                                               std::min((r + 1) * step, lastZ));
                  } else {
                    double x0, z0, x1, z1;
                    cellBox(r, c, x0, z0, x1, z1);
                    bound[k] = cellBound(hf, x0, z0, x1, z1);
                  }
                  if (bound[k] > bound[top]) top = k;
                }
              // The cell of the largest bound first (most often the block's largest deviation),
              // then every other cell whose bound is not below the largest found so far.
              auto exact = [&](size_t k) {
                double x0, z0, x1, z1;
                cellBox(r0 + int(k) / w, c0 + int(k) % w, x0, z0, x1, z1);
                return cellDeviation(hf, x0, z0, x1, z1, false);
              };
              double worst = exact(top);
              for (size_t k = 0; k < bound.size(); ++k)
                if (k != top && bound[k] >= worst) worst = std::max(worst, exact(k));
              bandMax[size_t(band) * size_t(blockCols) + size_t(i)] = float(worst);
            }
          }
        },
        1);
    for (int band = 0; band < bands; ++band)
      for (int i = 0; i < blockCols; ++i) {
        float& d = out[size_t(band * g / n) * size_t(blockCols) + size_t(i)];
        d = std::max(d, bandMax[size_t(band) * size_t(blockCols) + size_t(i)]);
      }
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
