#include "schemes/preprocess/tess_patterns.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <unordered_map>

namespace lb {
namespace {

int ceilDiv(int a, int b) {
  return (a + b - 1) / b;
}

// Every vertex of a pattern has one id, the same in every sub-patch that uses it: the corners
// (0,0), (1,0), (1,1), (0,1) are 0..3, then each edge's inner points, then the interior grid.
class VertexIds {
 public:
  VertexIds(const std::array<int, 4>& outer, int m0, int m1) : outer_(outer), m0_(m0), m1_(m1) {
    int next = 4;
    for (int k = 0; k < 4; ++k) {
      edgeBase_[size_t(k)] = next;
      next += std::max(0, outer[size_t(k)] - 1);
    }
    gridBase_ = next;
  }
  int count() const { return gridBase_ + std::max(0, m0_ - 1) * std::max(0, m1_ - 1); }

  // Point i (0..n) of edge k, counted along +u or +v whichever the edge runs along.
  int edge(int k, int i) const {
    const int n = outer_[size_t(k)];
    static constexpr int kFirst[4] = {0, 0, 1, 3}, kLast[4] = {3, 1, 2, 2};
    if (i == 0) return kFirst[k];
    if (i == n) return kLast[k];
    return edgeBase_[size_t(k)] + i - 1;
  }
  int grid(int a, int b) const { return gridBase_ + (b - 1) * (m0_ - 1) + (a - 1); }

  TessVertex vertex(int id) const {
    auto frac = [](int num, int den) { return TessFraction{uint16_t(num), uint16_t(den)}; };
    if (id < 4) return {frac(id == 1 || id == 2, 1), frac(id >= 2, 1)};
    if (id >= gridBase_) {
      const int g = id - gridBase_;
      return {frac(g % (m0_ - 1) + 1, m0_), frac(g / (m0_ - 1) + 1, m1_)};
    }
    int k = 3;
    while (id < edgeBase_[size_t(k)]) --k;
    const int n = outer_[size_t(k)], i = id - edgeBase_[size_t(k)] + 1;
    switch (k) {
      case 0:
        return {frac(0, 1), frac(i, n)};
      case 1:
        return {frac(i, n), frac(0, 1)};
      case 2:
        return {frac(1, 1), frac(i, n)};
      default:
        return {frac(i, n), frac(1, 1)};
    }
  }

 private:
  std::array<int, 4> outer_;
  int m0_, m1_;
  std::array<int, 4> edgeBase_{};
  int gridBase_ = 0;
};

// Collects one sub-patch: pattern ids become local indices in order of first use. `slots` maps
// ids to local indices (-1 unused) and is handed back all -1 for the next sub-patch.
class SubPatchBuilder {
 public:
  SubPatchBuilder(const VertexIds& ids, std::vector<int>& slots, TessSubPatch& out)
      : ids_(ids), slots_(slots), out_(out) {}
  ~SubPatchBuilder() {
    for (int id : used_) slots_[size_t(id)] = -1;
  }

  void triangle(int a, int b, int c) { out_.triangles.push_back({local(a), local(b), local(c)}); }

 private:
  uint8_t local(int id) {
    int& slot = slots_[size_t(id)];
    if (slot < 0) {
      slot = int(out_.vertices.size());
      out_.vertices.push_back(ids_.vertex(id));
      used_.push_back(id);
    }
    assert(slot < 256);
    return uint8_t(slot);
  }

  const VertexIds& ids_;
  std::vector<int>& slots_;
  TessSubPatch& out_;
  std::vector<int> used_;
};

// Stitches two parallel rows given as ids in the patch's counter-clockwise direction: `edge` on
// the patch border, `ring` on the first ring, the interior to the left of both.
void stitch(const std::vector<int>& edge, const std::vector<int>& ring, SubPatchBuilder& b) {
  const int p = int(edge.size()) - 1, q = int(ring.size()) - 1;
  if (p + q <= 0) return;
  const uint32_t steps = stripSteps(p, q);
  int i = 0, j = 0;
  for (int t = 0; t < p + q; ++t) {
    if (steps >> t & 1u) {
      b.triangle(edge[size_t(i)], edge[size_t(i + 1)], ring[size_t(j)]);
      ++i;
    } else {
      b.triangle(edge[size_t(i)], ring[size_t(j + 1)], ring[size_t(j)]);
      ++j;
    }
  }
}

// Ids from..to inclusive of one row, in either direction.
template <class F>
std::vector<int> row(int from, int to, F id) {
  std::vector<int> r;
  const int step = to >= from ? 1 : -1;
  for (int i = from;; i += step) {
    r.push_back(id(i));
    if (i == to) break;
  }
  return r;
}

// The k0 x k1 split of a pattern: where column x and row y start on the grid and on each edge.
struct Split {
  std::array<int, 4> n;
  int m0, m1, k0, k1;
  static int at(int count, int parts, int i) { return i * count / parts; }
  // Ring rows run over grid lines 1..m-1, so a piece's bound is clamped to them there.
  int ringU(int x) const { return std::clamp(at(m0, k0, x), 1, m0 - 1); }
  int ringV(int y) const { return std::clamp(at(m1, k1, y), 1, m1 - 1); }
};

// Sub-patch (x, y): its grid cells inside the first ring and its pieces of the border strips.
void subPatch(const Split& s, const VertexIds& ids, int x, int y, SubPatchBuilder& b) {
  const std::array<int, 4>& n = s.n;
  const int a0 = s.ringU(x), a1 = s.ringU(x + 1), b0 = s.ringV(y), b1 = s.ringV(y + 1);
  for (int bb = b0; bb < b1; ++bb)
    for (int aa = a0; aa < a1; ++aa) {
      // The (0,0)-(1,1) diagonal, as every grid footprint of the renderer.
      b.triangle(ids.grid(aa, bb), ids.grid(aa + 1, bb), ids.grid(aa + 1, bb + 1));
      b.triangle(ids.grid(aa, bb), ids.grid(aa + 1, bb + 1), ids.grid(aa, bb + 1));
    }
  auto edge = [&](int k) { return [&ids, k](int i) { return ids.edge(k, i); }; };
  // Strips in counter-clockwise order: v=0 runs +u, u=1 +v, v=1 -u, u=0 -v.
  if (y == 0)
    stitch(row(Split::at(n[1], s.k0, x), Split::at(n[1], s.k0, x + 1), edge(1)),
           row(a0, a1, [&](int a) { return ids.grid(a, 1); }), b);
  if (x == s.k0 - 1)
    stitch(row(Split::at(n[2], s.k1, y), Split::at(n[2], s.k1, y + 1), edge(2)),
           row(b0, b1, [&](int bb) { return ids.grid(s.m0 - 1, bb); }), b);
  if (y == s.k1 - 1)
    stitch(row(Split::at(n[3], s.k0, x + 1), Split::at(n[3], s.k0, x), edge(3)),
           row(a1, a0, [&](int a) { return ids.grid(a, s.m1 - 1); }), b);
  if (x == 0)
    stitch(row(Split::at(n[0], s.k1, y + 1), Split::at(n[0], s.k1, y), edge(0)),
           row(b1, b0, [&](int bb) { return ids.grid(1, bb); }), b);
}

}  // namespace

int equalSpacingFactor(float level) {
  if (!(level > 0.0f)) return 0;
  return int(std::ceil(std::min(level, float(kTessMaxFactor))));
}

uint32_t stripSteps(int p, int q) {
  assert(p >= 0 && q >= 0 && p + q <= 32);
  // Advance the row whose next segment's midpoint comes first along the strip, (i + 1/2) / p
  // against (j + 1/2) / q, the edge on a tie: triangles then lean no further than half a segment.
  uint32_t bits = 0;
  int i = 0, j = 0;
  for (int t = 0; t < p + q; ++t) {
    const bool alongEdge = i < p && (j == q || (2 * i + 1) * q <= (2 * j + 1) * p);
    if (alongEdge) {
      bits |= 1u << t;
      ++i;
    } else {
      ++j;
    }
  }
  return bits;
}

std::vector<uint32_t> stripTable(int cap) {
  std::vector<uint32_t> t;
  t.reserve(size_t(cap + 1) * size_t(cap + 1));
  for (int p = 0; p <= cap; ++p)
    for (int q = 0; q <= cap; ++q) t.push_back(stripSteps(p, q));
  return t;
}

TessPattern tessellateQuad(const TessFactors& factors, int cap) {
  assert(cap >= 2 && cap <= kTessCap);
  for (int f : factors.outer) assert(f >= 0 && f <= kTessMaxFactor);
  for (int f : factors.inner) assert(f >= 0 && f <= kTessMaxFactor);
  TessPattern out;
  out.factors = factors;
  const std::array<int, 4>& n = factors.outer;
  if (*std::min_element(n.begin(), n.end()) == 0) return out;
  int m0 = std::max(factors.inner[0], 1), m1 = std::max(factors.inner[1], 1);
  const bool allOne = m0 == 1 && m1 == 1 && n == std::array<int, 4>{1, 1, 1, 1};
  if (!allOne) m0 = std::max(m0, 2), m1 = std::max(m1, 2);
  out.factors.inner = {m0, m1};
  const VertexIds ids(n, m0, m1);
  std::vector<int> slots(size_t(ids.count()), -1);
  if (allOne) {
    out.columns = out.rows = 1;
    TessSubPatch& s = out.subPatches.emplace_back();
    SubPatchBuilder b(ids, slots, s);
    b.triangle(0, 1, 2);
    b.triangle(0, 2, 3);
    return out;
  }
  const Split split{n, m0, m1, std::max({ceilDiv(m0, cap), ceilDiv(n[1], cap), ceilDiv(n[3], cap)}),
                    std::max({ceilDiv(m1, cap), ceilDiv(n[0], cap), ceilDiv(n[2], cap)})};
  out.columns = split.k0;
  out.rows = split.k1;
  for (int y = 0; y < split.k1; ++y)
    for (int x = 0; x < split.k0; ++x) {
      TessSubPatch s;
      s.column = x;
      s.row = y;
      {
        SubPatchBuilder b(ids, slots, s);
        subPatch(split, ids, x, y, b);
      }
      if (!s.triangles.empty()) out.subPatches.push_back(std::move(s));
    }
  return out;
}

TessMesh weldPattern(const TessPattern& pattern) {
  TessMesh mesh;
  // Fractions are stored as made, never reduced, so equal points carry equal numbers.
  std::unordered_map<uint64_t, uint32_t> index;
  for (const TessSubPatch& s : pattern.subPatches) {
    std::vector<uint32_t> global(s.vertices.size());
    for (size_t i = 0; i < s.vertices.size(); ++i) {
      const TessVertex& v = s.vertices[i];
      const uint64_t key = uint64_t(v.u.num) << 48 | uint64_t(v.u.den) << 32 | uint64_t(v.v.num) << 16 | v.v.den;
      auto [it, added] = index.try_emplace(key, uint32_t(mesh.vertices.size()));
      if (added) mesh.vertices.push_back(v);
      global[i] = it->second;
    }
    for (const auto& t : s.triangles)
      for (uint8_t c : t) mesh.indices.push_back(global[c]);
  }
  return mesh;
}

}  // namespace lb
