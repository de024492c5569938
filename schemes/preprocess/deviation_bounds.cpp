#include "schemes/preprocess/deviation_bounds.h"

#include <algorithm>
#include <cmath>

#include "terrain/heightfield.h"

namespace lb {
namespace {

// Relative slack of a bound. Both the exact code and the bound round: coordinates up to 2^16
// texels carry errors near 2^-36 texel, times slopes and cross terms of a few times the largest
// height; a plane's terms carry a few ulps of their own size. 1e-9 of those magnitudes is
// thousands of times that and still far below any deviation worth a level.
constexpr double kSlack = 1e-9;

// Blocks of `size` cells meeting [lo, hi]: from lo's block to the one before the block boundary
// at or above hi (a box ending on a boundary needs no block beyond it), at least one, clamped to
// [0, blocks - 1] (the last block also holds the heightfield's last sample).
// (Inline floor and ceil: baseline x86-64 calls libm for std::floor, and this runs per item.)
void blockRange(double lo, double hi, int size, int blocks, int& first, int& last) {
  const double l = lo / size, h = hi / size;
  int f = int(l), c = int(h);
  f -= l < double(f);
  c += h > double(c);
  first = std::clamp(f, 0, blocks - 1);
  last = std::clamp(c - 1, first, blocks - 1);
}

}  // namespace

int DeviationBounds::fineFor(double sx, double sz) {
  const double cell = std::min(sx, sz) / 64;
  return cell >= 4 ? 4 : cell >= 2 ? 2 : 1;
}

void DeviationBounds::build(const Heightfield& hf, double x0, double z0, double x1, double z1, int fine) {
  maxAbs_ = 0;
  double poison = 0;  // NaN once a sample is NaN or infinite (v * 0)
  for (int m = 0; m < kLevels; ++m) {
    Level& l = levels_[m];
    l.size = fine << (2 * m);
    l.blocksX = std::max(1, (hf.width - 1 + l.size - 1) / l.size);
    l.blocksZ = std::max(1, (hf.height - 1 + l.size - 1) / l.size);
    int bx1, bz1;
    blockRange(x0, x1, l.size, l.blocksX, l.bx0, bx1);
    blockRange(z0, z1, l.size, l.blocksZ, l.bz0, bz1);
    l.nx = bx1 - l.bx0 + 1;
    l.nz = bz1 - l.bz0 + 1;
    l.blocks.resize(size_t(l.nx) * size_t(l.nz));
    for (int j = 0; j < l.nz; ++j)
      for (int i = 0; i < l.nx; ++i) {
        const int sx0 = (l.bx0 + i) * l.size, sz0 = (l.bz0 + j) * l.size;
        const int sx1 = std::min(sx0 + l.size, hf.width - 1), sz1 = std::min(sz0 + l.size, hf.height - 1);
        auto h = [&](int x, int z) { return double(hf.h[size_t(z) * size_t(hf.width) + size_t(x)]); };
        Block& b = l.blocks[size_t(j) * size_t(l.nx) + size_t(i)];
        b.x = sx0;
        b.z = sz0;
        b.wx = sx1 - sx0;
        b.wz = sz1 - sz0;
        // Any slope is valid; the corners' mean slope keeps the residuals small on a sloped block.
        b.qx = ((h(sx1, sz0) - h(sx0, sz0)) + (h(sx1, sz1) - h(sx0, sz1))) / (2.0 * b.wx);
        b.qz = ((h(sx0, sz1) - h(sx0, sz0)) + (h(sx1, sz1) - h(sx1, sz0))) / (2.0 * b.wz);
        double lo = INFINITY, hi = -INFINITY, big = 0;
        for (int z = sz0; z <= sz1; ++z) {
          const float* row = &hf.h[size_t(z) * size_t(hf.width)];
          const double rowPlane = b.qz * (z - sz0);
          for (int x = sx0; x <= sx1; ++x) {
            const double v = row[x], r = v - (b.qx * (x - sx0) + rowPlane);
            lo = std::min(lo, r);
            hi = std::max(hi, r);
            big = std::max(big, std::abs(v));
            poison += v * 0.0;
          }
        }
        b.lo = lo;
        b.hi = hi;
        maxAbs_ = std::max(maxAbs_, big);
      }
  }
  // Heights that are not finite (the loaders refuse them) leave min / max meaningless: no bounds.
  finite_ = poison == 0.0;
}

template <bool kChord, class Span>
double DeviationBounds::overBlocks(int level, double zlo, double zhi, Span&& span, glm::dvec2 p, double h0, double gx,
                                   double gz, glm::dvec2 d, double dh) const {
  if (!finite_) return INFINITY;
  const Level& l = levels_[level];
  int iz0, iz1;
  blockRange(zlo, zhi, l.size, l.blocksZ, iz0, iz1);
  if (iz0 < l.bz0 || iz1 >= l.bz0 + l.nz) return INFINITY;  // outside what was built: no bound
  const double invDd = 1.0 / (d.x * d.x + d.y * d.y);
  double worst = 0, scale = std::abs(h0);
  double sum = 0;  // not finite once a term is (std::max would drop a NaN): then no bound
  for (int jz = iz0; jz <= iz1; ++jz) {
    double xlo, xhi;
    span(std::max(zlo, double(jz * l.size)), std::min(zhi, double((jz + 1) * l.size)), xlo, xhi);
    int ix0, ix1;
    blockRange(xlo, xhi, l.size, l.blocksX, ix0, ix1);
    if (ix0 < l.bx0 || ix1 >= l.bx0 + l.nx) return INFINITY;
    const Block* row = &l.blocks[size_t(jz - l.bz0) * size_t(l.nx)];
    for (int i = ix0 - l.bx0; i <= ix1 - l.bx0; ++i) {
      const Block& b = row[i];
      if (kChord) {  // the block's slope across the edge, the chord's along it
        const double lambda = (dh - (b.qx * d.x + b.qz * d.y)) * invDd;
        gx = b.qx + lambda * d.x;
        gz = b.qz + lambda * d.y;
      }
      // B - P = (B - Q) + (Q - P), Q - P = (q - g).(x - origin) - P(origin).
      const double ex = (b.qx - gx) * b.wx, ez = (b.qz - gz) * b.wz;
      const double tx = gx * (b.x - p.x), tz = gz * (b.z - p.y);
      const double k = h0 + tx + tz;
      const double upper = b.hi + std::max(ex, 0.0) + std::max(ez, 0.0) - k;
      const double lower = b.lo + std::min(ex, 0.0) + std::min(ez, 0.0) - k;
      worst = std::max({worst, upper, -lower});
      scale = std::max(scale, std::abs(tx) + std::abs(tz) + std::abs(ex) + std::abs(ez));
      sum += upper + lower + scale;
    }
  }
  if (!std::isfinite(sum)) return INFINITY;
  return worst + kSlack * (worst + scale + maxAbs_);
}

// The finest block size that covers a box of this extent with at most 5 x 5 blocks.
int DeviationBounds::levelFor(double extent) const {
  return extent <= levels_[1].size ? 0 : extent <= levels_[2].size ? 1 : 2;
}

double DeviationBounds::edge(glm::dvec2 a, glm::dvec2 b, double ha, double hb) const {
  const glm::dvec2 d = b - a;
  if (d.x == 0.0 && d.y == 0.0) return INFINITY;
  const double xlo = std::min(a.x, b.x), xhi = std::max(a.x, b.x), zlo = std::min(a.y, b.y), zhi = std::max(a.y, b.y);
  auto box = [&](double, double, double& lo, double& hi) { lo = xlo, hi = xhi; };
  return overBlocks<true>(levelFor(std::max(xhi - xlo, zhi - zlo)), zlo, zhi, box, a, ha, 0, 0, d, hb - ha);
}

double DeviationBounds::edgeAlong(glm::dvec2 a, glm::dvec2 b, double ha, double hb) const {
  const glm::dvec2 d = b - a;
  if (d.x == 0.0 && d.y == 0.0) return INFINITY;
  const double xlo = std::min(a.x, b.x), xhi = std::max(a.x, b.x), zlo = std::min(a.y, b.y), zhi = std::max(a.y, b.y);
  // The segment's x over a row of blocks, widened by far more than its rounding: more blocks
  // than needed only loosens the bound.
  auto along = [&](double z0, double z1, double& lo, double& hi) {
    if (d.y == 0.0) {
      lo = xlo, hi = xhi;
      return;
    }
    const double x0 = a.x + (z0 - a.y) * d.x / d.y, x1 = a.x + (z1 - a.y) * d.x / d.y;
    const double margin = 1e-6 * (1.0 + std::abs(x0) + std::abs(x1));
    lo = std::max(xlo, std::min(x0, x1) - margin);
    hi = std::min(xhi, std::max(x0, x1) + margin);
  };
  return overBlocks<true>(0, zlo, zhi, along, a, ha, 0, 0, d, hb - ha);
}

double DeviationBounds::triangle(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c, double ha, double hb, double hc) const {
  // The plane exactly as the interior scan computes it (the same degenerate test: it scans nothing).
  const glm::dvec2 e1 = b - a, e2 = c - a;
  const double det = e1.x * e2.y - e1.y * e2.x;
  if (std::abs(det) < 1e-12) return 0.0;
  const double gx = ((hb - ha) * e2.y - (hc - ha) * e1.y) / det;
  const double gz = ((hc - ha) * e1.x - (hb - ha) * e2.x) / det;
  const double xlo = std::min({a.x, b.x, c.x}), xhi = std::max({a.x, b.x, c.x});
  const double zlo = std::min({a.y, b.y, c.y}), zhi = std::max({a.y, b.y, c.y});
  auto box = [&](double, double, double& lo, double& hi) { lo = xlo, hi = xhi; };
  return overBlocks<false>(levelFor(std::max(xhi - xlo, zhi - zlo)), zlo, zhi, box, a, ha, gx, gz, {0, 0}, 0);
}

}  // namespace lb
