#include "schemes/preprocess/tess_deviation.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <thread>
#include <vector>

#include "schemes/preprocess/deviation_bounds.h"
#include "terrain/heightfield.h"
#include "terrain/parallel_rows.h"

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

// int(std::floor(v)) for v inside the int range (texel coordinates are), without the libm call
// that baseline x86-64 (no SSE4.1 roundsd) makes of std::floor: this runs once per edge segment.
inline int floorToInt(double v) {
  const int i = int(v);
  return v < double(i) ? i - 1 : i;
}

// int(std::ceil(v)) likewise (per row of every triangle's interior scan).
inline int ceilToInt(double v) {
  const int i = int(v);
  return v > double(i) ? i + 1 : i;
}

inline Cell cellAt(const Heightfield& hf, dvec2 p) {
  Cell c;
  c.x = std::clamp(floorToInt(p.x), 0, std::max(hf.width - 2, 0));
  c.z = std::clamp(floorToInt(p.y), 0, std::max(hf.height - 2, 0));
  if (hf.width >= 2 && hf.height >= 2) {  // the four samples are inside: index without at()'s clamps
    const float* r0 = &hf.h[size_t(c.z) * size_t(hf.width) + size_t(c.x)];
    const float* r1 = r0 + hf.width;
    c.h00 = r0[0];
    c.h10 = r0[1];
    c.h01 = r1[0];
    c.h11 = r1[1];
  } else {
    c.h00 = hf.at(c.x, c.z);
    c.h10 = hf.at(c.x + 1, c.z);
    c.h01 = hf.at(c.x, c.z + 1);
    c.h11 = hf.at(c.x + 1, c.z + 1);
  }
  return c;
}

double heightAt(const Heightfield& hf, dvec2 p) {
  return cellAt(hf, p).at(p);
}

// Parameters t in (0, 1) where segment coordinate a -> b crosses the integer grid lines, in
// increasing t: (g - a) / (b - a) for the integers g strictly between a and b. The quotient is
// monotone in g (increasing for a < b, decreasing for a > b), so walking g in the right
// direction yields the values already sorted, with no list and no sort.
// The crossings are in (0, 1]: |g - a| < |b - a| and a correctly rounded quotient cannot pass 1.
struct Crossings {
  double a, b, g = 0, step = 0, lo = 0, hi = 0;
  double t = 0;  // the current crossing's parameter, computed once per crossing
  bool any = false;
  Crossings(double a_, double b_) : a(a_), b(b_) {
    if (a == b) return;
    lo = std::min(a, b);
    hi = std::max(a, b);
    // floor(lo) + 1, + 2, ... < hi (the integers strictly between), upwards or downwards from
    // ceil(hi) - 1, the largest of them; integers stay exact in double.
    g = a < b ? std::floor(lo) + 1.0 : std::ceil(hi) - 1.0;
    step = a < b ? 1.0 : -1.0;
    update();
  }
  double value() const { return t; }
  void next() {
    g += step;
    update();
  }
  void update() {
    any = g > lo && g < hi;
    if (any) t = (g - a) / (b - a);
  }
};

// The pieces of segment p->q inside one heightfield cell each: calls piece(t0, t1, cell) for
// consecutive breakpoints t0 < t1 (0, 1 and both axes' grid-line crossings, in increasing order:
// a three-way merge of sorted sequences is the sorted list a sort of all of them gives; values,
// not positions, matter), with the cell that holds the piece's midpoint.
template <class Piece>
inline void edgePieces(const Heightfield& hf, dvec2 p, dvec2 q, Piece&& piece) {
  dvec2 d = q - p;
  Crossings cx(p.x, q.x), cz(p.y, q.y);
  double t0 = 0.0;
  bool endDone = false;
  while (!endDone) {
    double t1;
    const bool hasX = cx.any, hasZ = cz.any;
    if (hasX && (!hasZ || cx.value() <= cz.value())) {
      t1 = cx.value();
      cx.next();
    } else if (hasZ) {
      t1 = cz.value();
      cz.next();
    } else {
      t1 = 1.0;
      endDone = true;
    }
    if (t1 > t0) piece(t0, t1, cellAt(hf, p + d * (0.5 * (t0 + t1))));
    t0 = std::max(t0, t1);
  }
}

// Largest |B - chord| over one piece [t0, t1] of segment p + d t inside cell (x, z) with corner
// heights h00..h11, where the chord runs from hp to hq: both ends and, when inside, the
// stationary point of the quadratic.
inline double pieceDeviation(double px, double py, double dx, double dy, double hp, double hq, double t0, double t1,
                             double x, double z, double h00, double h10, double h01, double h11) {
  const double tw = h00 - h10 - h01 + h11;
  auto dev = [&](double t) {
    const double fx = (px + dx * t) - x, fz = (py + dy * t) - z;
    return (h00 + (h10 - h00) * fx + (h01 - h00) * fz + tw * fx * fz) - (hp + t * (hq - hp));
  };
  const double ends = std::max(std::abs(dev(t0)), std::abs(dev(t1)));
  const double quad = tw * dx * dy;  // t^2 coefficient of B along the segment
  if (quad == 0.0) return ends;
  const double fx0 = px - x, fz0 = py - z;
  const double lin = (h10 - h00) * dx + (h01 - h00) * dy + tw * (dx * fz0 + fx0 * dy) - (hq - hp);
  const double ts0 = -lin / (2.0 * quad);
  return ts0 > t0 && ts0 < t1 ? std::max(ends, std::abs(dev(ts0))) : ends;
}

// Largest |B - chord| along segment p->q, where the chord interpolates B(p), B(q) linearly.
double edgeDeviation(const Heightfield& hf, dvec2 p, dvec2 q, double hp, double hq) {
  const dvec2 d = q - p;
  double worst = 0;
  edgePieces(hf, p, q, [&](double t0, double t1, const Cell& c) {
    worst = std::max(worst, pieceDeviation(p.x, p.y, d.x, d.y, hp, hq, t0, t1, c.x, c.z, c.h00, c.h10, c.h01, c.h11));
  });
  return worst;
}

// The part of triangleDeviation inside the triangle: heightfield samples against the plane
// through the three vertices (heights ha, hb, hc), over sample rows [zFrom, zTo] (clamped to the
// triangle's). 0 for a degenerate triangle.
double interiorDeviation(const Heightfield& hf, dvec2 a, dvec2 b, dvec2 c, double ha, double hb, double hc,
                         int zFrom = 0, int zTo = std::numeric_limits<int>::max()) {
  double worst = 0;
  dvec2 e1 = b - a, e2 = c - a;
  double det = e1.x * e2.y - e1.y * e2.x;
  if (std::abs(det) < 1e-12) return worst;  // degenerate: its edges are all there is
  // Plane gradient: P(x) = ha + g . (x - a).
  double gx = ((hb - ha) * e2.y - (hc - ha) * e1.y) / det;
  double gz = ((hc - ha) * e1.x - (hb - ha) * e2.x) / det;
  // Samples inside, row by row (cost follows the triangle's area, not its bounding box).
  dvec2 v[3] = {a, b, c};
  double zlo = std::max(0.0, std::min({a.y, b.y, c.y})),
         zhi = std::min(double(hf.height - 1), std::max({a.y, b.y, c.y}));
  for (int z = std::max(ceilToInt(zlo), zFrom), zEnd = std::min(floorToInt(zhi), zTo); z <= zEnd; ++z) {
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
    const int x0 = ceilToInt(xlo), x1 = floorToInt(xhi);
    if (x0 > x1) continue;
    // z is in [0, height - 1] and x in [0, width - 1] here: the row is indexed directly.
    const float* row = &hf.h[size_t(z) * size_t(hf.width)];
    // plane = (ha + gx * (x - a.x)) + gz * (z - a.y), evaluated left to right as written before;
    // the row term is the same double on every sample. Four running maxima break the dependency
    // chain; max is exact and order-free, so the result is the same bits.
    const double rowTerm = gz * (z - a.y);
    double w0 = 0, w1 = 0, w2 = 0, w3 = 0;
    int x = x0;
    for (; x + 3 <= x1; x += 4) {
      w0 = std::max(w0, std::abs(double(row[x]) - (ha + gx * (x - a.x) + rowTerm)));
      w1 = std::max(w1, std::abs(double(row[x + 1]) - (ha + gx * (x + 1 - a.x) + rowTerm)));
      w2 = std::max(w2, std::abs(double(row[x + 2]) - (ha + gx * (x + 2 - a.x) + rowTerm)));
      w3 = std::max(w3, std::abs(double(row[x + 3]) - (ha + gx * (x + 3 - a.x) + rowTerm)));
    }
    for (; x <= x1; ++x) w0 = std::max(w0, std::abs(double(row[x]) - (ha + gx * (x - a.x) + rowTerm)));
    worst = std::max({worst, w0, w1, w2, w3});
  }
  return worst;
}

}  // namespace

double triangleDeviation(const Heightfield& hf, dvec2 a, dvec2 b, dvec2 c, bool rowsInParallel) {
  double ha = heightAt(hf, a), hb = heightAt(hf, b), hc = heightAt(hf, c);
  double worst =
      std::max({edgeDeviation(hf, a, b, ha, hb), edgeDeviation(hf, b, c, hb, hc), edgeDeviation(hf, c, a, hc, ha)});
  if (!rowsInParallel) return std::max(worst, interiorDeviation(hf, a, b, c, ha, hb, hc, 0, hf.height - 1));
  // Each band's maximum, then theirs: max is exact and order-free, so the bands change nothing.
  const int z0 = std::max(0, ceilToInt(std::min({a.y, b.y, c.y})));
  const int z1 = std::min(hf.height - 1, floorToInt(std::max({a.y, b.y, c.y})));
  if (z1 < z0) return worst;
  std::vector<double> bands(size_t(z1 - z0 + 1), 0.0);
  parallelRows(
      z1 - z0 + 1,
      [&](int r0, int r1) { bands[size_t(r0)] = interiorDeviation(hf, a, b, c, ha, hb, hc, z0 + r0, z0 + r1 - 1); },
      256);
  for (double w : bands) worst = std::max(worst, w);
  return worst;
}

namespace {

// D3D11 reference tessellator: the order in which points split a half edge (ruler function),
// which drives the stitching of a transition strip between two rows of different density.
constexpr int kRulerOrder[33] = {0, 32, 16, 8,  17, 4,  18, 9,  19, 2,  20, 10, 21, 5,  22, 11, 23,
                                 1, 24, 12, 25, 6,  26, 13, 27, 3,  28, 14, 29, 7,  30, 15, 31};

// Triangles of the outermost ring along one edge, in strip coordinates (s along the edge, t
// inward), for inner level L >= 2 and edge level E (powers of two): outer row s = j / E at t = 0,
// inner row s = (i + 1) / L at t = 1 / L (the first inner ring, corner to corner); L = 2 has a
// single inner point, the patch centre. Both halves are walked from their corner as the
// reference tessellator's StitchTransition does for even factors.
void stripTriangles(int L, int E, std::vector<dvec2>& out) {
  auto o = [&](int j) { return dvec2(double(j) / E, 0.0); };
  auto in = [&](int i) { return dvec2(double(i + 1) / L, 1.0 / L); };
  int inHalf = L / 2, outHalf = E / 2, oi = 0, ii = 0;
  auto advOut = [&] {
    out.insert(out.end(), {o(oi), o(oi + 1), in(ii)});
    ++oi;
  };
  auto advIn = [&] {
    out.insert(out.end(), {in(ii), o(oi), in(ii + 1)});
    ++ii;
  };
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
  for (int j = 0; j < E; ++j)
    out.insert(out.end(), {dvec2(double(j) / E, 0), dvec2(double(j + 1) / E, 0), dvec2(0.5, 0.5)});
}

// Strip (s, t) -> patch (u, v) for edge u=0, v=0, u=1, v=1.
dvec2 toPatch(int edge, dvec2 st) {
  switch (edge) {
    case 0:
      return {st.y, st.x};
    case 1:
      return {st.x, st.y};
    case 2:
      return {1.0 - st.y, st.x};
    default:
      return {st.x, 1.0 - st.y};
  }
}

void edgeTriangles(int L, int E, int edge, std::vector<dvec2>& out) {
  std::vector<dvec2> st;
  if (L == 1)
    fanTriangles(E, st);
  else
    stripTriangles(L, E, st);
  for (dvec2 p : st) out.push_back(toPatch(edge, p));
}

// Cells of the L-grid inside the first ring, each with both diagonals (4 triangles); level 1
// without finer edges is the single cell with both diagonals.
void interiorTriangles(int L, std::vector<dvec2>& out) {
  int lo = L == 1 ? 0 : 1, hi = L == 1 ? 1 : L - 1;
  for (int b = lo; b < hi; ++b)
    for (int a = lo; a < hi; ++a) {
      dvec2 c00(double(a) / L, double(b) / L), c10(double(a + 1) / L, double(b) / L),
          c01(double(a) / L, double(b + 1) / L), c11(double(a + 1) / L, double(b + 1) / L);
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

namespace {

// One level's triangles reduced to what the maximum needs: each directed edge once and each
// ordered triangle once (neighbouring cells' both-diagonal triangles share edges, and every
// finer edge level repeats the strip's inner row). dev(p, k) is the maximum over the triangles
// of max(edges, interior), so taking every distinct edge and interior once gives the same value,
// bit for bit: the same deviations are computed from the same coordinates, and max is exact.
// Direction matters (p->q and q->p round differently), so only identical directed edges merge.
struct LevelWork {
  std::vector<std::array<dvec2, 2>> edges;
  std::vector<std::array<dvec2, 3>> triangles;
};

template <size_t N>
bool lessPoints(const std::array<dvec2, N>& l, const std::array<dvec2, N>& r) {
  for (size_t i = 0; i < N; ++i) {
    if (l[i].x != r[i].x) return l[i].x < r[i].x;
    if (l[i].y != r[i].y) return l[i].y < r[i].y;
  }
  return false;
}

template <size_t N>
void sortUnique(std::vector<std::array<dvec2, N>>& v) {
  std::sort(v.begin(), v.end(), lessPoints<N>);
  v.erase(std::unique(v.begin(), v.end(),
                      [](const auto& l, const auto& r) { return !lessPoints<N>(l, r) && !lessPoints<N>(r, l); }),
          v.end());
}

LevelWork levelWork(const std::vector<dvec2>& tri) {
  LevelWork w;
  for (size_t i = 0; i + 2 < tri.size(); i += 3) {
    w.triangles.push_back({tri[i], tri[i + 1], tri[i + 2]});
    for (int e = 0; e < 3; ++e) w.edges.push_back({tri[i + size_t(e)], tri[i + size_t((e + 1) % 3)]});
  }
  sortUnique(w.edges);
  sortUnique(w.triangles);
  return w;
}

// Every distinct vertex, directed edge and triangle of the 7 levels in patch (u, v), and which
// of them each level takes. The lists do not depend on the patch: built once per table.
struct PatchPattern {
  std::vector<dvec2> vertices;
  std::vector<std::array<uint32_t, 2>> edges;      // vertex indices
  std::vector<uint32_t> reverse;                   // index of the edge b->a of edge a->b, or itself
  std::vector<std::array<uint32_t, 3>> triangles;  // vertex indices
  std::vector<std::vector<uint32_t>> levelEdges, levelTriangles;
};

PatchPattern patchPattern() {
  std::vector<LevelWork> perLevel;
  for (int k = 0; k < kErrboundLevels; ++k) {
    int L = 1 << k;
    std::vector<dvec2> tri;
    interiorTriangles(L, tri);
    for (int E = L; E <= 64; E *= 2)
      for (int e = 0; e < 4; ++e) edgeTriangles(L, E, e, tri);
    perLevel.push_back(levelWork(tri));
  }
  PatchPattern pp;
  // Levels share edges too (a strip's outer row at edge level E is the same at every level <= E):
  // each patch computes every distinct edge once, and each level takes the maximum over its own.
  std::vector<std::array<dvec2, 2>> allEdges;
  for (const LevelWork& w : perLevel) allEdges.insert(allEdges.end(), w.edges.begin(), w.edges.end());
  sortUnique(allEdges);
  pp.levelEdges.resize(perLevel.size());
  for (size_t k = 0; k < perLevel.size(); ++k)
    for (const auto& e : perLevel[k].edges)
      pp.levelEdges[k].push_back(
          uint32_t(std::lower_bound(allEdges.begin(), allEdges.end(), e, lessPoints<2>) - allEdges.begin()));
  // The same for triangles (level 0's fans and level 1's strips share some).
  std::vector<std::array<dvec2, 3>> allTriangles;
  for (const LevelWork& w : perLevel) allTriangles.insert(allTriangles.end(), w.triangles.begin(), w.triangles.end());
  sortUnique(allTriangles);
  pp.levelTriangles.resize(perLevel.size());
  for (size_t k = 0; k < perLevel.size(); ++k)
    for (const auto& tr : perLevel[k].triangles)
      pp.levelTriangles[k].push_back(uint32_t(
          std::lower_bound(allTriangles.begin(), allTriangles.end(), tr, lessPoints<3>) - allTriangles.begin()));
  // Edges and triangles share their vertices: each patch computes a vertex's texel position
  // and height once (the same expressions on the same (u, v), so the same bits as per use).
  for (const auto& e : allEdges) pp.vertices.insert(pp.vertices.end(), e.begin(), e.end());
  for (const auto& tr : allTriangles) pp.vertices.insert(pp.vertices.end(), tr.begin(), tr.end());
  auto lessVertex = [](dvec2 l, dvec2 r) { return l.x != r.x ? l.x < r.x : l.y < r.y; };
  std::sort(pp.vertices.begin(), pp.vertices.end(), lessVertex);
  pp.vertices.erase(std::unique(pp.vertices.begin(), pp.vertices.end()), pp.vertices.end());
  auto vertexIndex = [&](dvec2 v) {
    return uint32_t(std::lower_bound(pp.vertices.begin(), pp.vertices.end(), v, lessVertex) - pp.vertices.begin());
  };
  for (const auto& e : allEdges) {
    pp.edges.push_back({vertexIndex(e[0]), vertexIndex(e[1])});
    auto r = std::lower_bound(allEdges.begin(), allEdges.end(), std::array<dvec2, 2>{e[1], e[0]}, lessPoints<2>);
    const bool found = r != allEdges.end() && r->at(0) == e[1] && r->at(1) == e[0];
    pp.reverse.push_back(uint32_t(found ? r - allEdges.begin() : &e - allEdges.data()));
  }
  for (const auto& tr : allTriangles)
    pp.triangles.push_back({vertexIndex(tr[0]), vertexIndex(tr[1]), vertexIndex(tr[2])});
  return pp;
}

// One patch's vertices in texel coordinates with their bilinear heights.
struct PatchVertices {
  std::vector<dvec2> tex;
  std::vector<double> height;
  void place(const Heightfield& hf, const PatchPattern& pp, dvec2 origin, double sx, double sz) {
    tex.resize(pp.vertices.size());
    height.resize(pp.vertices.size());
    for (size_t v = 0; v < pp.vertices.size(); ++v) {
      tex[v] = origin + dvec2(pp.vertices[v].x * sx, pp.vertices[v].y * sz);
      height[v] = heightAt(hf, tex[v]);
    }
  }
};

// Runs patch(origin, sx, sz, out) for every patch on all terrain threads: origin is the patch's
// corner in texels, out its kErrboundLevels entries. makeWorker() gives each thread its own
// patch function (with its own scratch).
template <class MakeWorker>
DeviationTable forEachPatch(const Heightfield& hf, int grid, MakeWorker&& makeWorker) {
  DeviationTable t;
  t.grid = grid;
  t.dev.assign(size_t(grid) * size_t(grid) * kErrboundLevels, 0.0f);
  const double sx = double(hf.width - 1) / grid, sz = double(hf.height - 1) / grid;
  std::atomic<int> next{0};
  auto work = [&] {
    auto patch = makeWorker();
    for (int p; (p = next++) < grid * grid;)
      patch(dvec2((p % grid) * sx, (p / grid) * sz), sx, sz, &t.dev[size_t(p) * kErrboundLevels]);
  };
  const unsigned threads = unsigned(terrainThreads());
  std::vector<std::thread> pool;
  for (unsigned i = 1; i < threads; ++i) pool.emplace_back(work);
  work();
  for (std::thread& th : pool) th.join();
  return t;
}

// Rounded up so the float the shader reads never undercuts the double bound.
float roundedUp(double worst) {
  return std::nextafter(float(worst), INFINITY);
}

}  // namespace

DeviationTable tessDeviationReference(const Heightfield& hf, int grid) {
  const PatchPattern pp = patchPattern();
  return forEachPatch(hf, grid, [&] {
    std::vector<double> edgeDev(pp.edges.size()), triangleDev(pp.triangles.size());
    PatchVertices pv;
    return [&, edgeDev, triangleDev, pv](dvec2 origin, double sx, double sz, float* out) mutable {
      pv.place(hf, pp, origin, sx, sz);
      for (size_t i = 0; i < pp.edges.size(); ++i) {
        const uint32_t ia = pp.edges[i][0], ib = pp.edges[i][1];
        edgeDev[i] = edgeDeviation(hf, pv.tex[ia], pv.tex[ib], pv.height[ia], pv.height[ib]);
      }
      for (size_t i = 0; i < pp.triangles.size(); ++i) {
        const uint32_t ia = pp.triangles[i][0], ib = pp.triangles[i][1], ic = pp.triangles[i][2];
        triangleDev[i] =
            interiorDeviation(hf, pv.tex[ia], pv.tex[ib], pv.tex[ic], pv.height[ia], pv.height[ib], pv.height[ic]);
      }
      for (int k = 0; k < kErrboundLevels; ++k) {
        double worst = 0;
        for (uint32_t i : pp.levelEdges[size_t(k)]) worst = std::max(worst, edgeDev[i]);
        for (uint32_t i : pp.levelTriangles[size_t(k)]) worst = std::max(worst, triangleDev[i]);
        out[k] = roundedUp(worst);
      }
    };
  });
}

DeviationTable tessDeviation(const Heightfield& hf, int grid) {
  // Every patch has the same ~50,000 edges and triangles whatever its size; below 32 texels a
  // side the exact ones are about as cheap as their bounds (measured: equal at 32, the bounds
  // 1.8x slower at 16, 1.5x faster at 46), so small patches take the straightforward table.
  const double side = std::min(double(hf.width - 1), double(hf.height - 1)) / grid;
  return side >= 32 ? tessDeviationBounded(hf, grid) : tessDeviationReference(hf, grid);
}

DeviationTable tessDeviationBounded(const Heightfield& hf, int grid) {
  if (hf.width < 2 || hf.height < 2) return tessDeviationReference(hf, grid);  // no cell to bound
  const PatchPattern pp = patchPattern();
  return forEachPatch(hf, grid, [&] {
    // Per edge / triangle: its bound, and its exact deviation once computed (NaN before).
    std::vector<double> edgeBound(pp.edges.size()), triangleBound(pp.triangles.size());
    std::vector<double> edgeDev(pp.edges.size()), triangleDev(pp.triangles.size()), edgeAlong(pp.edges.size());
    PatchVertices pv;
    DeviationBounds bounds;
    return [&, edgeBound, triangleBound, edgeDev, triangleDev, edgeAlong, pv, bounds](dvec2 origin, double sx,
                                                                                      double sz, float* out) mutable {
      pv.place(hf, pp, origin, sx, sz);
      bounds.build(hf, origin.x, origin.y, origin.x + sx, origin.y + sz, DeviationBounds::fineFor(sx, sz));
      // An edge and its reverse have one bound: the slack covers either direction's rounding.
      for (size_t i = 0; i < pp.edges.size(); ++i) {
        const uint32_t ia = pp.edges[i][0], ib = pp.edges[i][1];
        edgeBound[i] = pp.reverse[i] < i ? edgeBound[pp.reverse[i]]
                                         : bounds.edge(pv.tex[ia], pv.tex[ib], pv.height[ia], pv.height[ib]);
        edgeDev[i] = edgeAlong[i] = NAN;
      }
      for (size_t i = 0; i < pp.triangles.size(); ++i) {
        const uint32_t ia = pp.triangles[i][0], ib = pp.triangles[i][1], ic = pp.triangles[i][2];
        triangleBound[i] =
            bounds.triangle(pv.tex[ia], pv.tex[ib], pv.tex[ic], pv.height[ia], pv.height[ib], pv.height[ic]);
        triangleDev[i] = NAN;
      }
      // A long edge's box bound is loose: its tighter bound along the edge first.
      // Comparisons read "cannot beat" as bound <= worst, so that a NaN bound is computed.
      auto edgeBeats = [&](uint32_t i, double worst) {
        if (edgeBound[i] <= worst) return false;
        if (std::isnan(edgeAlong[i])) {
          const uint32_t ia = pp.edges[i][0], ib = pp.edges[i][1];
          edgeAlong[i] = edgeAlong[pp.reverse[i]] =
              bounds.edgeAlong(pv.tex[ia], pv.tex[ib], pv.height[ia], pv.height[ib]);
        }
        return !(edgeAlong[i] <= worst);
      };
      auto exactEdge = [&](uint32_t i) {
        if (std::isnan(edgeDev[i])) {
          const uint32_t ia = pp.edges[i][0], ib = pp.edges[i][1];
          edgeDev[i] = edgeDeviation(hf, pv.tex[ia], pv.tex[ib], pv.height[ia], pv.height[ib]);
        }
        return edgeDev[i];
      };
      auto exactTriangle = [&](uint32_t i) {
        if (std::isnan(triangleDev[i])) {
          const uint32_t ia = pp.triangles[i][0], ib = pp.triangles[i][1], ic = pp.triangles[i][2];
          triangleDev[i] =
              interiorDeviation(hf, pv.tex[ia], pv.tex[ib], pv.tex[ic], pv.height[ia], pv.height[ib], pv.height[ic]);
        }
        return triangleDev[i];
      };
      for (int k = 0; k < kErrboundLevels; ++k) {
        const std::vector<uint32_t>& es = pp.levelEdges[size_t(k)];
        const std::vector<uint32_t>& ts = pp.levelTriangles[size_t(k)];
        // Seed the running maximum with the item of the largest bound (likely among the largest
        // deviations), then compute only what its bound lets beat the maximum so far. A skipped
        // item's deviation is <= its bound <= the maximum: the maximum is the same double.
        double worst = 0, top = -1;
        bool topIsEdge = true;
        uint32_t topIndex = 0;
        for (uint32_t i : es)
          if (edgeBound[i] > top) top = edgeBound[i], topIsEdge = true, topIndex = i;
        for (uint32_t i : ts)
          if (triangleBound[i] > top) top = triangleBound[i], topIsEdge = false, topIndex = i;
        if (top >= 0) worst = std::max(worst, topIsEdge ? exactEdge(topIndex) : exactTriangle(topIndex));
        for (uint32_t i : es)
          if (edgeBeats(i, worst)) worst = std::max(worst, exactEdge(i));
        for (uint32_t i : ts)
          if (!(triangleBound[i] <= worst)) worst = std::max(worst, exactTriangle(i));
        out[k] = roundedUp(worst);
      }
    };
  });
}

}  // namespace lb
