// Tessellation patterns for the mesh-shader path (schemes/preprocess/tess_patterns.h), checked on
// the CPU since lavapipe has no mesh shaders: counts against the disc formula and Euler, total area,
// winding, watertight edges whose border is exactly each factor's segments, bit-identical shared
// edges between neighbours, and the split above the cap within the mesh-shader output limits.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <set>
#include <string>
#include <tuple>

#include "random.h"
#include "schemes/preprocess/tess_patterns.h"

using namespace lb;

namespace {

constexpr int kC = kTessCap;
// The largest piece the cap allows: 4C border and (C-1)^2 inner vertices.
constexpr int kPieceVertices = 4 * kC + (kC - 1) * (kC - 1);
constexpr int kPieceTriangles = 4 * kC + 2 * (kC - 1) * (kC - 1) - 2;

// Inner factors as the sphere scheme sets them: the larger of the two edges along each direction.
TessFactors sphereFactors(int n0, int n1, int n2, int n3) {
  return {{n0, n1, n2, n3}, {std::max(n1, n3), std::max(n0, n2)}};
}

std::string str(const TessFactors& f) {
  std::string s = "outer";
  for (int n : f.outer) s += " " + std::to_string(n);
  return s + " inner " + std::to_string(f.inner[0]) + " " + std::to_string(f.inner[1]);
}

int ceilDiv(int a, int b) {
  return (a + b - 1) / b;
}

// The counts stated in the header, from the factors alone (inner 1 counts as 2 unless all are 1).
struct Counts {
  int vertices = 0, triangles = 0;
};
Counts expectedCounts(const TessFactors& f) {
  int border = 0, m0 = std::max(f.inner[0], 1), m1 = std::max(f.inner[1], 1);
  for (int n : f.outer) border += n;
  if (border != 4 || m0 != 1 || m1 != 1) m0 = std::max(m0, 2), m1 = std::max(m1, 2);
  return {border + (m0 - 1) * (m1 - 1), border + 2 * (m0 - 1) * (m1 - 1) - 2};
}

uint32_t bits(float f) {
  uint32_t b;
  std::memcpy(&b, &f, sizeof b);
  return b;
}

// (b - a) x (c - a) of exact fractions: each difference is p / q with q <= 64^2, so the sign of
// p1 p2 q3 q4 - p3 p4 q1 q2 is exact in 64 bits; also the area in double.
struct Cross {
  int64_t num = 0, den = 1;
};
Cross cross(const TessVertex& a, const TessVertex& b, const TessVertex& c) {
  auto diff = [](TessFraction x, TessFraction y, int64_t& p, int64_t& q) {
    p = int64_t(x.num) * y.den - int64_t(y.num) * x.den;
    q = int64_t(x.den) * y.den;
  };
  int64_t p1, q1, p2, q2, p3, q3, p4, q4;
  diff(b.u, a.u, p1, q1);
  diff(c.v, a.v, p2, q2);
  diff(c.u, a.u, p3, q3);
  diff(b.v, a.v, p4, q4);
  return {p1 * p2 * q3 * q4 - p3 * p4 * q1 * q2, q1 * q2 * q3 * q4};
}

// Which border a vertex lies on, counter-clockwise (v=0, u=1, v=1, u=0), and where along it in
// the counter-clockwise direction; -1 inside.
int side(const TessVertex& v, int from) {
  const float u = v.u.value(), w = v.v.value();
  for (int s = from; s < 4; ++s)
    if ((s == 0 && w == 0.0f) || (s == 1 && u == 1.0f) || (s == 2 && w == 1.0f) || (s == 3 && u == 0.0f)) return s;
  return -1;
}

// Everything the header promises of one pattern; "" when it all holds.
std::string problems(const TessFactors& f, int cap = kC, size_t* pieces = nullptr) {
  const TessPattern p = tessellateQuad(f, cap);
  if (pieces) *pieces = p.subPatches.size();
  const TessMesh m = weldPattern(p);
  const Counts want = expectedCounts(f);
  const int V = int(m.vertices.size()), T = int(m.indices.size() / 3);
  std::string bad;
  auto fail = [&](const std::string& what) {
    if (bad.empty()) bad = str(f) + ": " + what;
  };
  if (V != want.vertices || T != want.triangles)
    fail(std::to_string(V) + " vertices, " + std::to_string(T) + " triangles; the formula says " +
         std::to_string(want.vertices) + ", " + std::to_string(want.triangles));
  // Split: the header's k0 x k1, each piece within the cap's bound and the mesh limits, compact.
  const int m0 = p.factors.inner[0], m1 = p.factors.inner[1];
  const int k0 = std::max({ceilDiv(m0, cap), ceilDiv(f.outer[1], cap), ceilDiv(f.outer[3], cap)});
  const int k1 = std::max({ceilDiv(m1, cap), ceilDiv(f.outer[0], cap), ceilDiv(f.outer[2], cap)});
  if (p.columns != k0 || p.rows != k1) fail("split " + std::to_string(p.columns) + " x " + std::to_string(p.rows));
  for (const TessSubPatch& s : p.subPatches) {
    const int sv = int(s.vertices.size()), st = int(s.triangles.size());
    if (sv > kPieceVertices || st > kPieceTriangles || sv > kMeshMinOutputVertices || st > kMeshMinOutputPrimitives)
      fail("sub-patch " + std::to_string(s.column) + "," + std::to_string(s.row) + " has " + std::to_string(sv) +
           " vertices, " + std::to_string(st) + " triangles");
    std::vector<bool> used(s.vertices.size());
    for (const auto& t : s.triangles)
      for (uint8_t c : t) c < sv ? void(used[c] = true) : fail("local index past the sub-patch's vertices");
    if (std::count(used.begin(), used.end(), false)) fail("a sub-patch emits a vertex no triangle uses");
  }
  // Winding and area: every triangle counter-clockwise, and together they cover the unit square.
  double area = 0;
  for (int t = 0; t < T; ++t) {
    const Cross c = cross(m.vertices[m.indices[size_t(3 * t)]], m.vertices[m.indices[size_t(3 * t + 1)]],
                          m.vertices[m.indices[size_t(3 * t + 2)]]);
    if (c.num <= 0) fail("triangle " + std::to_string(t) + " is not counter-clockwise");
    area += 0.5 * double(c.num) / double(c.den);
  }
  if (std::abs(area - 1.0) > 1e-9) fail("total area " + std::to_string(area));
  // Watertight: each undirected edge in one triangle (an open edge) or two, run both ways (an inner
  // edge); sorted by the undirected edge, with the direction in the lowest bit.
  std::vector<uint64_t> edges;
  for (int t = 0; t < T; ++t)
    for (int e = 0; e < 3; ++e) {
      const uint64_t a = m.indices[size_t(3 * t + e)], b = m.indices[size_t(3 * t + (e + 1) % 3)];
      edges.push_back((std::min(a, b) << 32 | std::max(a, b)) << 1 | uint64_t(a > b));
    }
  std::sort(edges.begin(), edges.end());
  std::array<int, 4> open{};
  int E = 0;
  for (size_t i = 0; i < edges.size(); ++E) {
    size_t j = i + 1;
    while (j < edges.size() && edges[j] >> 1 == edges[i] >> 1) ++j;
    if (j - i == 2 && edges[i] != edges[i + 1]) {
      i = j;
      continue;
    }
    if (j - i > 1) fail("an edge is in more than two triangles or twice in one direction");
    // An open edge must be one segment of one side, walked counter-clockwise.
    const uint32_t lo = uint32_t(edges[i] >> 33), hi = uint32_t(edges[i] >> 1);
    const bool down = edges[i] & 1;
    const TessVertex &va = m.vertices[down ? hi : lo], &vb = m.vertices[down ? lo : hi];
    i = j;
    int s = side(va, 0);
    while (s >= 0 && side(vb, s) != s) s = side(va, s + 1);
    const int n = s < 0 ? 1 : f.outer[size_t((s + 1) % 4)];  // sides v=0, u=1, v=1, u=0 are edges 1, 2, 3, 0
    const float along = s < 0 ? 0 : (s % 2 == 0 ? vb.u.value() - va.u.value() : vb.v.value() - va.v.value());
    if (s < 0 || std::abs(along - (s < 2 ? 1.0f : -1.0f) / float(n)) > 1e-6f) {
      fail("open edge off the border or not one segment of it");
      continue;
    }
    ++open[size_t(s)];
  }
  // Open edges are distinct (each undirected edge counted once), so n of them on a side of factor
  // n are exactly its segments.
  for (int s = 0; s < 4; ++s)
    if (open[size_t(s)] != f.outer[size_t((s + 1) % 4)])
      fail("side " + std::to_string(s) + " has " + std::to_string(open[size_t(s)]) + " open edges");
  // Euler: a disc has V - E + F = 1, E counting each undirected edge once.
  if (V - E + T != 1) fail("V - E + F = " + std::to_string(V - E + T));
  return bad;
}

// Float bits of the coordinate along `edge` of every vertex on it, sorted.
std::vector<uint32_t> edgePoints(const TessFactors& f, int edge) {
  const TessMesh m = weldPattern(tessellateQuad(f));
  std::vector<uint32_t> out;
  for (const TessVertex& v : m.vertices) {
    const float u = v.u.value(), w = v.v.value();
    if ((edge == 0 && u == 0.0f) || (edge == 2 && u == 1.0f)) out.push_back(bits(w));
    if ((edge == 1 && w == 0.0f) || (edge == 3 && w == 1.0f)) out.push_back(bits(u));
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

// Every combination the sphere scheme can produce within the cap (inner = the larger parallel edge):
// 11^4 patterns, each one piece, with the stated counts, Euler, area, winding and closed edges.
TEST(TessPatterns, EverySphereCombinationUpToTheCapMatchesTheFormula) {
  int checked = 0;
  for (int a = 1; a <= kC; ++a)
    for (int b = 1; b <= kC; ++b)
      for (int c = 1; c <= kC; ++c)
        for (int d = 1; d <= kC; ++d) {
          const TessFactors f = sphereFactors(a, b, c, d);
          size_t pieces = 0;
          ASSERT_EQ(problems(f, kC, &pieces), "");
          ASSERT_EQ(pieces, 1u) << str(f) << ": within the cap, one piece";
          ++checked;
        }
  EXPECT_EQ(checked, 14641);
}

// Inner factors independent of the edges: every inner pair 0..C (0 and 1 round up) with every
// edge factor on every edge.
TEST(TessPatterns, EveryInnerPairUpToTheCapWithEveryEdgeFactor) {
  for (int m0 = 0; m0 <= kC; ++m0)
    for (int m1 = 0; m1 <= kC; ++m1)
      for (int n = 1; n <= kC; ++n) {
        const TessFactors f{{n, n % kC + 1, (n + 4) % kC + 1, (n + 8) % kC + 1}, {m0, m1}};
        ASSERT_EQ(problems(f), "");
      }
}

// Factor 1, inner 0 or 1, and culled patches.
TEST(TessPatterns, FactorOneAndDegenerateCases) {
  TessPattern p = tessellateQuad({{1, 1, 1, 1}, {1, 1}});
  EXPECT_EQ(weldPattern(p).vertices.size(), 4u);
  EXPECT_EQ(weldPattern(p).indices.size(), 6u) << "all ones: the quad as two triangles";
  EXPECT_EQ(problems({{1, 1, 1, 1}, {1, 1}}), "");
  EXPECT_EQ(problems({{1, 1, 1, 1}, {0, 0}}), "") << "inner 0 is inner 1";
  // An inner 1 beside a larger factor counts as 2, as in the tessellator: one centre point.
  const TessMesh one = weldPattern(tessellateQuad({{1, 3, 1, 1}, {1, 1}}));
  const TessMesh two = weldPattern(tessellateQuad({{1, 3, 1, 1}, {2, 2}}));
  EXPECT_EQ(one.vertices.size(), 7u);
  EXPECT_EQ(one.indices, two.indices);
  EXPECT_EQ(tessellateQuad({{1, 3, 1, 1}, {1, 1}}).factors.inner, (std::array<int, 2>{2, 2}));
  EXPECT_EQ(problems({{64, 1, 1, 1}, {1, 1}}), "") << "one fine edge fanned to the centre, split";
  EXPECT_EQ(problems({{1, 64, 1, 1}, {64, 1}}), "") << "inner 64 along a factor-1 edge";
  for (const TessFactors& culled : {TessFactors{{0, 4, 4, 4}, {4, 4}}, TessFactors{{4, 4, 4, 0}, {0, 0}}}) {
    const TessPattern c = tessellateQuad(culled);
    EXPECT_TRUE(c.subPatches.empty()) << "an outer factor of 0 culls the patch, as in the tessellator";
    EXPECT_EQ(c.columns * c.rows, 0);
  }
  EXPECT_EQ(equalSpacingFactor(0.0f), 0);
  EXPECT_EQ(equalSpacingFactor(-1.0f), 0);
  EXPECT_EQ(equalSpacingFactor(std::nanf("")), 0);
  EXPECT_EQ(equalSpacingFactor(0.3f), 1);
  EXPECT_EQ(equalSpacingFactor(2.0f), 2);
  EXPECT_EQ(equalSpacingFactor(2.01f), 3);
  EXPECT_EQ(equalSpacingFactor(100.0f), kTessMaxFactor);
}

// An independent check of the vertex set: equal factors n give exactly the (n+1)^2 grid i/n.
TEST(TessPatterns, EqualFactorsGiveTheFullGrid) {
  for (int n = 1; n <= kTessMaxFactor; ++n) {
    const TessMesh m = weldPattern(tessellateQuad({{n, n, n, n}, {n, n}}));
    std::set<std::pair<uint32_t, uint32_t>> got, want;
    for (const TessVertex& v : m.vertices) got.insert({bits(v.u.value()), bits(v.v.value())});
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) want.insert({bits(float(i) / float(n)), bits(float(j) / float(n))});
    EXPECT_EQ(got, want) << "n = " << n;
    EXPECT_EQ(m.indices.size(), size_t(6 * n * n)) << "n = " << n;
  }
}

// Two patches sharing an edge of factor n place its n + 1 points identically, bit for bit, and
// exactly at float(i) / float(n), whatever their other factors and whether either is split.
TEST(TessPatterns, NeighboursShareBitIdenticalEdgeVertices) {
  SplitMix64 rng{7};
  auto any = [&] { return 1 + int(rng.below(kTessMaxFactor)); };
  for (int n = 1; n <= kTessMaxFactor; ++n) {
    std::vector<uint32_t> exact;
    for (int i = 0; i <= n; ++i) exact.push_back(bits(float(i) / float(n)));
    std::sort(exact.begin(), exact.end());
    for (int trial = 0; trial < 3; ++trial) {
      // Left patch's u=1 edge against right patch's u=0 edge; lower's v=1 against upper's v=0.
      const TessFactors left = sphereFactors(any(), any(), n, any()), right = sphereFactors(n, any(), any(), any());
      const TessFactors lower = sphereFactors(any(), any(), any(), n), upper = sphereFactors(any(), n, any(), any());
      EXPECT_EQ(edgePoints(left, 2), exact) << str(left);
      EXPECT_EQ(edgePoints(right, 0), exact) << str(right);
      EXPECT_EQ(edgePoints(lower, 3), exact) << str(lower);
      EXPECT_EQ(edgePoints(upper, 1), exact) << str(upper);
    }
  }
}

// Past the cap: factors around multiples of the cap and up to 64, every pattern still has the
// whole pattern's counts, is closed and counter-clockwise, and every piece fits one workgroup.
TEST(TessPatterns, SplitsAboveTheCapWithinTheMeshOutputLimits) {
  const int kValues[] = {1, 2, 3, 10, 11, 12, 13, 22, 23, 24, 37, 63, 64};
  for (int s : kValues)
    for (int t : kValues) {
      ASSERT_EQ(problems(sphereFactors(s, t, s % 64 + 1, (t * 5) % 64 + 1)), "");
      ASSERT_EQ(problems({{s, t, (s * 7) % 64 + 1, t}, {t, s}}), "") << "inner not from the edges";
    }
  SplitMix64 rng{11};
  for (int trial = 0; trial < 200; ++trial) {
    TessFactors f;
    for (int& n : f.outer) n = 1 + int(rng.below(kTessMaxFactor));
    for (int& m : f.inner) m = int(rng.below(kTessMaxFactor + 1));
    ASSERT_EQ(problems(f), "");
  }
  // Factor 64 everywhere: 6 x 6 pieces of 10 or 11 segments, each at most the cap's bound.
  const TessPattern p = tessellateQuad({{64, 64, 64, 64}, {64, 64}});
  EXPECT_EQ(p.columns, 6);
  EXPECT_EQ(p.rows, 6);
  EXPECT_EQ(p.subPatches.size(), 36u);
  size_t most = 0;
  for (const TessSubPatch& s : p.subPatches) most = std::max(most, s.triangles.size());
  EXPECT_LE(most, size_t(kPieceTriangles));
  // A smaller cap splits sooner and keeps every promise.
  for (int cap = 2; cap < kC; ++cap) ASSERT_EQ(problems(sphereFactors(cap + 1, 2 * cap + 1, 5, 64), cap), "");
}

// Why 11: the largest single piece is 144 vertices and 242 triangles there, within 256 / 256;
// at 12 a whole pattern would need 288 triangles.
TEST(TessPatterns, TheCapIsTheLargestThatFitsTheMeshLimits) {
  EXPECT_EQ(kPieceVertices, 144);
  EXPECT_EQ(kPieceTriangles, 242);
  const TessMesh m = weldPattern(tessellateQuad({{kC, kC, kC, kC}, {kC, kC}}));
  EXPECT_EQ(int(m.vertices.size()), kPieceVertices);
  EXPECT_EQ(int(m.indices.size() / 3), kPieceTriangles);
  EXPECT_LE(kPieceTriangles, kMeshMinOutputPrimitives);
  const int next = kC + 1;
  EXPECT_GT(4 * next + 2 * (next - 1) * (next - 1) - 2, kMeshMinOutputPrimitives);
}

// The table a mesh shader uploads: one 32-bit word per strip shape, 576 bytes at the cap, each
// word p + q steps of which p advance along the edge.
TEST(TessPatterns, StripTableIsCompact) {
  const std::vector<uint32_t> table = stripTable();
  EXPECT_EQ(table.size() * sizeof(uint32_t), 576u);
  for (int p = 0; p <= kC; ++p)
    for (int q = 0; q <= kC; ++q) {
      const uint32_t w = table[size_t(p * (kC + 1) + q)];
      EXPECT_EQ(w, stripSteps(p, q));
      EXPECT_EQ(__builtin_popcount(w), p) << p << " x " << q;
      EXPECT_EQ(w >> (p + q), 0u) << p << " x " << q;
    }
  // Midpoint merge: equal rows alternate, and a single inner point is a fan.
  EXPECT_EQ(stripSteps(3, 3), 0b010101u);
  EXPECT_EQ(stripSteps(4, 0), 0b1111u);
  EXPECT_EQ(stripSteps(0, 4), 0u);
}

// The mesh shader's parallel form of the patterns (shaders/tess_piece.h: any vertex and any
// triangle of a piece from its index): the same split, and in every piece the generator's triangles
// in the generator's order, as points; empty where the generator leaves a piece out. And the most
// vertices and triangles a piece emits in that layout, over every factor combination: the
// constants the mesh shader declares as its outputs.
#define LB_TESS_STEPS(p, q) lb::stripSteps(p, q)
#define LB_TESS_BITCOUNT(x) __builtin_popcount(unsigned(x))
#include "shaders/tess_piece.h"

namespace {

using Point = std::pair<uint32_t, uint32_t>;  // bits of u, v

float fracValue(int num, int den) {  // as the mesh shader turns a fraction into a float
  return num == 0 ? 0.0f : num == den ? 1.0f : float(num) / float(den);
}

std::string pieceProblems(const TessFactors& f) {
  using namespace lb::tesspiece;
  const TessPattern p = tessellateQuad(f);
  const TessPatch t = tessPatch(f.outer[0], f.outer[1], f.outer[2], f.outer[3], f.inner[0], f.inner[1]);
  if (t.k0 != p.columns || t.k1 != p.rows)
    return str(f) + ": split " + std::to_string(t.k0) + " x " + std::to_string(t.k1) + ", generator " +
           std::to_string(p.columns) + " x " + std::to_string(p.rows);
  size_t next = 0;
  for (int index = 0; index < tessPieces(t); ++index) {
    const int x = index % t.k0, y = index / t.k0;
    const TessPiece q = tessPiece(t, x, y);
    const std::string where = str(f) + " piece " + std::to_string(x) + "," + std::to_string(y);
    if (q.vertices > LB_TESS_MAX_VERTICES || q.triangles > LB_TESS_MAX_TRIANGLES) return where + ": too large";
    const bool listed = next < p.subPatches.size() && p.subPatches[next].column == x && p.subPatches[next].row == y;
    if (!listed) {
      if (q.triangles != 0) return where + ": triangles where the generator has none";
      continue;
    }
    const TessSubPatch& s = p.subPatches[next++];
    if (size_t(q.triangles) != s.triangles.size())
      return where + ": " + std::to_string(q.triangles) + " triangles, generator " + std::to_string(s.triangles.size());
    std::vector<Point> mine;
    for (int i = 0; i < q.vertices; ++i) {
      const TessFrac v = tessVertex(t, q, i);
      mine.push_back({bits(fracValue(v.un, v.ud)), bits(fracValue(v.vn, v.vd))});
    }
    for (size_t k = 0; k < s.triangles.size(); ++k) {
      const TessTri tri = tessTriangle(t, q, int(k));
      for (int c : {tri.a, tri.b, tri.c})
        if (c < 0 || c >= q.vertices) return where + ": index out of the piece";
      const int got[3] = {tri.a, tri.b, tri.c};
      for (int c = 0; c < 3; ++c) {
        const TessVertex& w = s.vertices[s.triangles[k][size_t(c)]];
        if (mine[size_t(got[c])] != Point{bits(w.u.value()), bits(w.v.value())})
          return where + ": triangle " + std::to_string(k) + " differs";
      }
    }
  }
  return next == p.subPatches.size() ? "" : str(f) + ": the generator has pieces past the split";
}

}  // namespace

TEST(TessPatterns, MeshShaderPieceLayoutIsTheGenerators) {
  for (int a = 1; a <= kC; ++a)
    for (int b = 1; b <= kC; ++b)
      for (int c = 1; c <= kC; ++c)
        for (int d = 1; d <= kC; ++d) ASSERT_EQ(pieceProblems(sphereFactors(a, b, c, d)), "");
  for (int m0 = 0; m0 <= kC; ++m0)
    for (int m1 = 0; m1 <= kC; ++m1)
      for (int n = 1; n <= kTessMaxFactor; ++n) ASSERT_EQ(pieceProblems({{n, n, n, n}, {m0, m1}}), "");
  const int kValues[] = {1, 2, 3, 10, 11, 12, 13, 22, 23, 24, 37, 63, 64};
  for (int s : kValues)
    for (int t : kValues) {
      ASSERT_EQ(pieceProblems(sphereFactors(s, t, s % 64 + 1, (t * 5) % 64 + 1)), "");
      ASSERT_EQ(pieceProblems({{s, t, (s * 7) % 64 + 1, t}, {t, s}}), "");
      ASSERT_EQ(pieceProblems({{1, 64, 1, 64}, {s, t}}), "");
    }
  SplitMix64 rng{23};
  for (int trial = 0; trial < 2000; ++trial) {
    TessFactors f;
    for (int& n : f.outer) n = 1 + int(rng.below(kTessMaxFactor));
    for (int& m : f.inner) m = int(rng.below(kTessMaxFactor + 1));
    ASSERT_EQ(pieceProblems(f), "");
  }
}

// A piece's vertices are its block plus each touched edge's points: the block and the horizontal
// edges' points follow from the factors along u (inner along u, edges v=0 and v=1) and the piece's
// column, the rest from those along v and its row. Every column of every factor triple along u,
// against every row of every triple along v, bounds the whole space of 65^2 x 64^4 combinations.
TEST(TessPatterns, MeshShaderOutputsBoundEveryPiece) {
  struct Side {
    int span, firstEdge, lastEdge;  // grid points across the block; edge points of the first and last strip
    bool first, last;
    bool operator<(const Side& o) const {
      return std::tie(span, firstEdge, lastEdge, first, last) <
             std::tie(o.span, o.firstEdge, o.lastEdge, o.first, o.last);
    }
  };
  std::set<Side> sides;
  for (int inner = 0; inner <= kTessMaxFactor; ++inner)
    for (int lo = 1; lo <= kTessMaxFactor; ++lo)
      for (int hi = 1; hi <= kTessMaxFactor; ++hi) {
        // Along u: inner m0, edge v=0 (n1) and edge v=1 (n3); the same arithmetic serves v.
        const lb::tesspiece::TessPatch t = lb::tesspiece::tessPatch(2, lo, 2, hi, inner, 2);
        for (int x = 0; x < t.k0; ++x) {
          const int a0 = lb::tesspiece::tessRing(t.m0, t.k0, x), a1 = lb::tesspiece::tessRing(t.m0, t.k0, x + 1);
          const int e1 = lb::tesspiece::tessAt(lo, t.k0, x + 1) - lb::tesspiece::tessAt(lo, t.k0, x);
          const int e3 = lb::tesspiece::tessAt(hi, t.k0, x + 1) - lb::tesspiece::tessAt(hi, t.k0, x);
          sides.insert({a1 - a0 + 1, e1 + 1, e3 + 1, x == 0, x == t.k0 - 1});
        }
      }
  int most = 0;
  for (const Side& u : sides)
    for (const Side& v : sides)
      most = std::max(most, u.span * v.span + (v.first ? u.firstEdge : 0) + (v.last ? u.lastEdge : 0) +
                                (u.first ? v.firstEdge : 0) + (u.last ? v.lastEdge : 0));
  EXPECT_EQ(most, LB_TESS_MAX_VERTICES) << "the declared outputs are the bound";
  EXPECT_LE(LB_TESS_MAX_VERTICES, kMeshMinOutputVertices);
  EXPECT_EQ(LB_TESS_MAX_TRIANGLES, kPieceTriangles) << "the triangles are the generator's";
  std::printf("[TessPatterns] the mesh shader's pieces: at most %d vertices (declared %d)\n", most,
              LB_TESS_MAX_VERTICES);
}
