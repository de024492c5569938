#include "terrain/tess_deviation.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>

#include "terrain/heightfield.h"

namespace lb {
namespace {

using glm::dvec2;

// Bilinear height in texel coordinates with the cell fixed (so a piece of an edge inside one
// cell is one quadratic); the cell is clamped as Heightfield::sample / terrainHeight() clamp it.
struct Cell {
  int x = 0, z = 0;
  double h00 = 0, h10 = 0, h01 = 0, h11 = 0;
  double at(dvec2 p) const {
    double fx = p.x - x, fz = p.y - z;
    return h00 + (h10 - h00) * fx + (h01 - h00) * fz + (h00 - h10 - h01 + h11) * fx * fz;
  }
};

Cell cellAt(const Heightfield& hf, dvec2 p) {
  Cell c;
  c.x = std::clamp(int(std::floor(p.x)), 0, std::max(hf.width - 2, 0));
  c.z = std::clamp(int(std::floor(p.y)), 0, std::max(hf.height - 2, 0));
  c.h00 = hf.at(c.x, c.z);
  c.h10 = hf.at(c.x + 1, c.z);
  c.h01 = hf.at(c.x, c.z + 1);
  c.h11 = hf.at(c.x + 1, c.z + 1);
  return c;
}

double heightAt(const Heightfield& hf, dvec2 p) { return cellAt(hf, p).at(p); }

// Largest |B - chord| along segment p->q, where the chord interpolates B(p), B(q) linearly.
double edgeDeviation(const Heightfield& hf, dvec2 p, dvec2 q, double hp, double hq) {
  dvec2 d = q - p;
  thread_local std::vector<double> ts;
  ts.assign({0.0, 1.0});
  for (int axis = 0; axis < 2; ++axis) {
    double a = axis ? p.y : p.x, b = axis ? q.y : q.x;
    if (a == b) continue;
    for (double g = std::floor(std::min(a, b)) + 1.0; g < std::max(a, b); g += 1.0) ts.push_back((g - a) / (b - a));
  }
  std::sort(ts.begin(), ts.end());
  int n = int(ts.size());
  double worst = 0;
  for (int i = 0; i + 1 < n; ++i) {
    double t0 = ts[i], t1 = ts[i + 1];
    if (t1 <= t0) continue;
    Cell c = cellAt(hf, p + d * (0.5 * (t0 + t1)));
    auto dev = [&](double t) { return c.at(p + d * t) - (hp + t * (hq - hp)); };
    worst = std::max({worst, std::abs(dev(t0)), std::abs(dev(t1))});
    double tw = c.h00 - c.h10 - c.h01 + c.h11;
    double quad = tw * d.x * d.y;  // t^2 coefficient of B along the segment
    if (quad != 0.0) {
      double fx0 = p.x - c.x, fz0 = p.y - c.z;
      double lin = (c.h10 - c.h00) * d.x + (c.h01 - c.h00) * d.y + tw * (d.x * fz0 + fx0 * d.y) - (hq - hp);
      double ts0 = -lin / (2.0 * quad);
      if (ts0 > t0 && ts0 < t1) worst = std::max(worst, std::abs(dev(ts0)));
    }
  }
  return worst;
}

}  // namespace

double triangleDeviation(const Heightfield& hf, dvec2 a, dvec2 b, dvec2 c) {
  double ha = heightAt(hf, a), hb = heightAt(hf, b), hc = heightAt(hf, c);
  double worst = std::max({edgeDeviation(hf, a, b, ha, hb), edgeDeviation(hf, b, c, hb, hc), edgeDeviation(hf, c, a, hc, ha)});
  dvec2 e1 = b - a, e2 = c - a;
  double det = e1.x * e2.y - e1.y * e2.x;
  if (std::abs(det) < 1e-12) return worst;  // degenerate: its edges are all there is
  // Plane gradient: P(x) = ha + g . (x - a).
  double gx = ((hb - ha) * e2.y - (hc - ha) * e1.y) / det;
  double gz = ((hc - ha) * e1.x - (hb - ha) * e2.x) / det;
  // Samples inside, row by row (cost follows the triangle's area, not its bounding box).
  dvec2 v[3] = {a, b, c};
  double zlo = std::max(0.0, std::min({a.y, b.y, c.y})), zhi = std::min(double(hf.height - 1), std::max({a.y, b.y, c.y}));
  for (int z = int(std::ceil(zlo)); z <= int(std::floor(zhi)); ++z) {
    double xlo = INFINITY, xhi = -INFINITY;
    for (int e = 0; e < 3; ++e) {
      dvec2 p = v[e], q = v[(e + 1) % 3];
      if ((z < std::min(p.y, q.y)) || (z > std::max(p.y, q.y))) continue;
      double x = p.y == q.y ? p.x : p.x + (q.x - p.x) * (z - p.y) / (q.y - p.y);
      if (p.y == q.y) {
        xlo = std::min({xlo, p.x, q.x});
        xhi = std::max({xhi, p.x, q.x});
      } else {
        xlo = std::min(xlo, x);
        xhi = std::max(xhi, x);
      }
    }
    xlo = std::max(xlo, 0.0);
    xhi = std::min(xhi, double(hf.width - 1));
    for (int x = int(std::ceil(xlo)); x <= int(std::floor(xhi)); ++x) {
      double plane = ha + gx * (x - a.x) + gz * (z - a.y);
      worst = std::max(worst, std::abs(double(hf.at(x, z)) - plane));
    }
  }
  return worst;
}

namespace {

// D3D11 reference tessellator: the order in which points split a half edge (ruler function),
// which drives the stitching of a transition strip between two rows of different density.
constexpr int kRulerOrder[33] = {0,  32, 16, 8,  17, 4,  18, 9,  19, 2,  20, 10, 21, 5,  22, 11, 23,
                                 1,  24, 12, 25, 6,  26, 13, 27, 3,  28, 14, 29, 7,  30, 15, 31};

// Triangles of the outermost ring along one edge, in strip coordinates (s along the edge, t
// inward), for inner level L >= 2 and edge level E (powers of two): outer row s = j / E at t = 0,
// inner row s = (i + 1) / L at t = 1 / L (the first inner ring, corner to corner); L = 2 has a
// single inner point, the patch centre. Both halves are walked from their corner as the
// reference tessellator's StitchTransition does for even factors.
void stripTriangles(int L, int E, std::vector<dvec2>& out) {
  auto o = [&](int j) { return dvec2(double(j) / E, 0.0); };
  auto in = [&](int i) { return dvec2(double(i + 1) / L, 1.0 / L); };
  int inHalf = L / 2, outHalf = E / 2, oi = 0, ii = 0;
  auto advOut = [&] { out.insert(out.end(), {o(oi), o(oi + 1), in(ii)}); ++oi; };
  auto advIn = [&] { out.insert(out.end(), {in(ii), o(oi), in(ii + 1)}); ++ii; };
  if (kRulerOrder[0] < outHalf) advOut();
  for (int i = 1; i <= 32; ++i) {
    if (kRulerOrder[i] < inHalf) advIn();
    if (kRulerOrder[i] < outHalf) advOut();
  }
  for (int i = 32; i >= 1; --i) {
    if (kRulerOrder[i] < outHalf) advOut();
    if (kRulerOrder[i] < inHalf) advIn();
  }
  if (kRulerOrder[0] < outHalf) advOut();
}

// Level 1 with a finer edge: the inner "ring" is the centre point and the edge fans to it.
void fanTriangles(int E, std::vector<dvec2>& out) {
  for (int j = 0; j < E; ++j) out.insert(out.end(), {dvec2(double(j) / E, 0), dvec2(double(j + 1) / E, 0), dvec2(0.5, 0.5)});
}

// Strip (s, t) -> patch (u, v) for edge u=0, v=0, u=1, v=1.
dvec2 toPatch(int edge, dvec2 st) {
  switch (edge) {
    case 0: return {st.y, st.x};
    case 1: return {st.x, st.y};
    case 2: return {1.0 - st.y, st.x};
    default: return {st.x, 1.0 - st.y};
  }
}

void edgeTriangles(int L, int E, int edge, std::vector<dvec2>& out) {
  std::vector<dvec2> st;
  if (L == 1) fanTriangles(E, st);
  else stripTriangles(L, E, st);
  for (dvec2 p : st) out.push_back(toPatch(edge, p));
}

// Cells of the L-grid inside the first ring, each with both diagonals (4 triangles); level 1
// without finer edges is the single cell with both diagonals.
void interiorTriangles(int L, std::vector<dvec2>& out) {
  int lo = L == 1 ? 0 : 1, hi = L == 1 ? 1 : L - 1;
  for (int b = lo; b < hi; ++b)
    for (int a = lo; a < hi; ++a) {
      dvec2 c00(double(a) / L, double(b) / L), c10(double(a + 1) / L, double(b) / L), c01(double(a) / L, double(b + 1) / L),
          c11(double(a + 1) / L, double(b + 1) / L);
      out.insert(out.end(), {c00, c10, c11, c00, c11, c01, c00, c10, c01, c10, c11, c01});
    }
}

}  // namespace

std::vector<dvec2> patchTriangles(int k, const int edges[4]) {
  int L = 1 << k;
  std::vector<dvec2> out;
  bool allOne = L == 1 && edges[0] == 1 && edges[1] == 1 && edges[2] == 1 && edges[3] == 1;
  if (allOne || L > 1) interiorTriangles(L, out);
  if (!allOne)
    for (int e = 0; e < 4; ++e) edgeTriangles(L, edges[e], e, out);
  return out;
}

DeviationTable tessDeviation(const Heightfield& hf, int grid) {
  DeviationTable t;
  t.grid = grid;
  t.dev.assign(size_t(grid) * size_t(grid) * kErrboundLevels, 0.0f);
  // The triangle lists do not depend on the patch: build them once per level, in patch (u, v).
  std::vector<std::vector<dvec2>> perLevel(kErrboundLevels);
  for (int k = 0; k < kErrboundLevels; ++k) {
    int L = 1 << k;
    interiorTriangles(L, perLevel[size_t(k)]);
    for (int E = L; E <= 64; E *= 2)
      for (int e = 0; e < 4; ++e) edgeTriangles(L, E, e, perLevel[size_t(k)]);
  }
  const double sx = double(hf.width - 1) / grid, sz = double(hf.height - 1) / grid;
  std::atomic<int> next{0};
  auto work = [&] {
    for (int p; (p = next++) < grid * grid;) {
      dvec2 origin((p % grid) * sx, (p / grid) * sz);
      for (int k = 0; k < kErrboundLevels; ++k) {
        const std::vector<dvec2>& tri = perLevel[size_t(k)];
        double worst = 0;
        for (size_t i = 0; i + 2 < tri.size(); i += 3) {
          auto tex = [&](dvec2 uv) { return origin + dvec2(uv.x * sx, uv.y * sz); };
          worst = std::max(worst, triangleDeviation(hf, tex(tri[i]), tex(tri[i + 1]), tex(tri[i + 2])));
        }
        // Rounded up so the float the shader reads never undercuts the double bound.
        t.dev[size_t(p) * kErrboundLevels + size_t(k)] = std::nextafter(float(worst), INFINITY);
      }
    }
  };
  unsigned threads = std::max(1u, std::min(16u, std::thread::hardware_concurrency()));
  std::vector<std::thread> pool;
  for (unsigned i = 1; i < threads; ++i) pool.emplace_back(work);
  work();
  for (std::thread& th : pool) th.join();
  return t;
}

}  // namespace lb
