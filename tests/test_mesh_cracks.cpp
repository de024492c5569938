// The triangle-based crack check (metrics/mesh_cracks.h) on meshes built the way the instanced-grid
// vertex shader builds them: world x, z = origin + lattice * cell in float (one product, one sum),
// height a function of the float x, z, so shared vertices are bit-identical. Every planted defect
// has an exact expected count.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>

#include "metrics/mesh_cracks.h"

using namespace lb;

namespace {

// A lattice whose cell and origin are not exactly representable sums, so that diagonal lattice
// points land off their rounded lines and the tolerance is exercised.
struct Lattice {
  float originX = -500.25f, originZ = 123.4f;
  float cell = 1000.0f / 96.0f;

  float coord(double i, float origin) const {
    const float local = float(i) * cell;  // two separate roundings, as the shader's `precise`
    return origin + local;
  }
  glm::vec3 at(double i, double j) const {
    const float x = coord(i, originX), z = coord(j, originZ);
    return {x, 7.0f * std::sin(0.013f * x) * std::cos(0.011f * z) + 0.002f * x, z};
  }
  // Terrain lattice [0, ni] x [0, nj].
  MeshCrackBounds bounds(int ni, int nj) const {
    return {{coord(0, originX), coord(0, originZ)}, {coord(ni, originX), coord(nj, originZ)}};
  }
};

using Mesh = std::vector<glm::vec3>;

void tri(Mesh& m, glm::vec3 a, glm::vec3 b, glm::vec3 c) {
  m.insert(m.end(), {a, b, c});
}

// Lattice point -> lattice point (a morph); identity by default.
using Morph = std::pair<double, double> (*)(int, int);
std::pair<double, double> noMorph(int i, int j) {
  return {i, j};
}

// Cells of `step` lattice units over [i0, i0 + nx*step] x [j0, j0 + nz*step], each split along
// its (i, j)-(i+1, j+1) diagonal: (00, 10, 11) and (00, 11, 01).
void grid(Mesh& m, const Lattice& l, int i0, int j0, int nx, int nz, int step, Morph morph = noMorph) {
  auto v = [&](int i, int j) {
    auto [mi, mj] = morph(i, j);
    return l.at(mi, mj);
  };
  for (int cz = 0; cz < nz; ++cz)
    for (int cx = 0; cx < nx; ++cx) {
      const int i = i0 + cx * step, j = j0 + cz * step;
      tri(m, v(i, j), v(i + step, j), v(i + step, j + step));
      tri(m, v(i, j), v(i + step, j + step), v(i, j + step));
    }
}

// Removes the two triangles of the step-1 cell whose lower corner is lattice (i, j).
void removeCell(Mesh& m, const Lattice& l, int i, int j) {
  const glm::vec3 c = l.at(i, j);
  for (size_t t = 0; t < m.size() / 3;) {
    if (m[3 * t] == c) {
      m.erase(m.begin() + long(3 * t), m.begin() + long(3 * t + 3));
    } else {
      ++t;
    }
  }
}

void expectSame(const MeshCrackResult& a, const MeshCrackResult& b) {
  EXPECT_EQ(a.triangles, b.triangles);
  EXPECT_EQ(a.invalidTriangles, b.invalidTriangles);
  EXPECT_EQ(a.degenerateTriangles, b.degenerateTriangles);
  EXPECT_EQ(a.collapsedTriangles, b.collapsedTriangles);
  EXPECT_EQ(a.openEdges, b.openEdges);
  EXPECT_EQ(a.borderEdges, b.borderEdges);
  EXPECT_EQ(a.unpairedEdges, b.unpairedEdges);
  EXPECT_EQ(a.cracks, b.cracks);
  EXPECT_EQ(a.crackSites, b.crackSites);
}

// The counts every result keeps: the open edges split into three.
void expectConsistent(const MeshCrackResult& r) {
  EXPECT_EQ(r.openEdges, r.borderEdges + r.unpairedEdges + r.cracks);
  EXPECT_LE(r.crackSites * 2, r.cracks);
  EXPECT_LE(r.collapsedTriangles, r.degenerateTriangles);
}

}  // namespace

TEST(MeshCracks, WatertightGridHasOnlyBorderEdges) {
  Lattice l;
  Mesh m;
  grid(m, l, 0, 0, 16, 16, 1);
  MeshCrackResult r = meshCracks(m, l.bounds(16, 16));
  expectConsistent(r);
  EXPECT_EQ(r.triangles, 512);
  EXPECT_EQ(r.openEdges, 64);
  EXPECT_EQ(r.borderEdges, 64);
  EXPECT_EQ(r.unpairedEdges, 0);
  EXPECT_EQ(r.cracks, 0);
  EXPECT_EQ(r.crackSites, 0);
  EXPECT_EQ(r.degenerateTriangles, 0);
  EXPECT_GT(r.tolerance, 0.0);
}

TEST(MeshCracks, BorderEdgesAreIgnoredAndOnlyTheBorder) {
  Lattice l;
  Mesh m;
  grid(m, l, 0, 0, 16, 8, 1);
  // The rectangle from exact arithmetic may differ from the float expression by an ulp: still border.
  MeshCrackBounds exact{
      {float(double(l.originX)), float(double(l.originZ))},
      {float(double(l.originX) + 16.0 * double(l.cell)), float(double(l.originZ) + 8.0 * double(l.cell))}};
  MeshCrackResult r = meshCracks(m, exact);
  expectConsistent(r);
  EXPECT_EQ(r.borderEdges, 48);
  EXPECT_EQ(r.unpairedEdges, 0);
  // A terrain larger than the mesh: the outline is interior now, open and unpaired, still no crack.
  MeshCrackResult wider = meshCracks(m, l.bounds(32, 32));
  expectConsistent(wider);
  EXPECT_EQ(wider.borderEdges, 24);  // z = 0 and x = 0 are still on the border
  EXPECT_EQ(wider.unpairedEdges, 24);
  EXPECT_EQ(wider.cracks, 0);
}

TEST(MeshCracks, HeightGapAtOneVertex) {
  Lattice l;
  Mesh m;
  grid(m, l, 0, 0, 16, 16, 1);
  // Cell (5, 5)'s first triangle (55, 65, 66) sees vertex 66 one unit higher than everyone else:
  // its edges 65-66 and 66-55 no longer pair; their partners 65-66 (cell (6, 5)) and 55-66 (the
  // cell's other triangle) are open too. Two edges seen at two heights: 4 crack edges, 2 sites.
  const size_t t = 2 * (5 * 16 + 5);
  ASSERT_EQ(m[3 * t + 2], l.at(6, 6));
  m[3 * t + 2].y += 1.0f;
  MeshCrackResult r = meshCracks(m, l.bounds(16, 16));
  expectConsistent(r);
  EXPECT_EQ(r.borderEdges, 64);
  EXPECT_EQ(r.cracks, 4);
  EXPECT_EQ(r.crackSites, 2);
  EXPECT_EQ(r.unpairedEdges, 0);
}

TEST(MeshCracks, TJunctionBetweenFineAndCoarsePatch) {
  Lattice l;
  Mesh m;
  grid(m, l, 0, 0, 8, 8, 1);  // fine: x in [0, 8]
  grid(m, l, 8, 0, 4, 4, 2);  // coarse: x in [8, 16]
  MeshCrackResult r = meshCracks(m, l.bounds(16, 8));
  expectConsistent(r);
  // Along x = 8: 4 coarse edges, each overlapped by its 2 fine halves.
  EXPECT_EQ(r.cracks, 12);
  EXPECT_EQ(r.crackSites, 4);
  EXPECT_EQ(r.unpairedEdges, 0);
  EXPECT_EQ(r.borderEdges, 24 + 12);
  EXPECT_EQ(r.degenerateTriangles, 0);

  // Closed by a strip of zero-area triangles A-M-B: every edge pairs.
  for (int k = 0; k < 4; ++k) tri(m, l.at(8, 2 * k), l.at(8, 2 * k + 1), l.at(8, 2 * k + 2));
  MeshCrackResult closed = meshCracks(m, l.bounds(16, 8));
  expectConsistent(closed);
  EXPECT_EQ(closed.cracks, 0);
  EXPECT_EQ(closed.crackSites, 0);
  EXPECT_EQ(closed.unpairedEdges, 0);
  EXPECT_EQ(closed.borderEdges, 36);
  EXPECT_EQ(closed.degenerateTriangles, 4);
  EXPECT_EQ(closed.collapsedTriangles, 0);
}

TEST(MeshCracks, DiagonalTJunctionsWithinRounding) {
  // Every 2x2 cell: a coarse triangle below its diagonal, two fine ones above meeting at the
  // diagonal's lattice midpoint. Cell sides pair exactly between cells; each diagonal is a T-junction.
  Lattice l;
  Mesh m;
  const int n = 48;
  long offLine = 0;
  for (int cz = 0; cz < n; ++cz)
    for (int cx = 0; cx < n; ++cx) {
      const int i = 2 * cx, j = 2 * cz;
      const glm::vec3 a = l.at(i, j), b = l.at(i + 2, j + 2), mid = l.at(i + 1, j + 1);
      tri(m, a, l.at(i + 2, j), b);
      tri(m, a, mid, l.at(i, j + 2));
      tri(m, mid, b, l.at(i, j + 2));
      const double cross = (double(b.x) - a.x) * (double(mid.z) - a.z) - (double(b.z) - a.z) * (double(mid.x) - a.x);
      offLine += cross != 0.0;
    }
  std::printf("diagonal T-junctions whose midpoint is off the rounded line: %ld of %d\n", offLine, n * n);
  EXPECT_GT(offLine, 0);  // otherwise this test would not exercise the tolerance
  MeshCrackResult r = meshCracks(m, l.bounds(2 * n, 2 * n));
  expectConsistent(r);
  EXPECT_EQ(r.cracks, 3L * n * n);
  EXPECT_EQ(r.crackSites, long(n) * n);
  EXPECT_EQ(r.unpairedEdges, 0);
  EXPECT_EQ(r.borderEdges, 4L * n);
}

namespace {
// CDLOD's morph at k = 1: odd lattice coordinates move to the lower even neighbour.
std::pair<double, double> fullMorph(int i, int j) {
  return {i - (i & 1), j - (j & 1)};
}
// k = 1 on the column x = 8 that borders the coarse patch, k = 1/2 elsewhere: interior vertices
// leave the lattice, boundary ones move along the boundary.
std::pair<double, double> partialMorph(int i, int j) {
  const double k = i == 8 ? 1.0 : 0.5;
  return {i - k * (i & 1), j - k * (j & 1)};
}
}  // namespace

TEST(MeshCracks, MorphCollapsedBlocksCancel) {
  Lattice l;
  Mesh m;
  grid(m, l, 0, 0, 8, 8, 1, fullMorph);  // 16 blocks of 2x2 cells, each collapsed to one coarse cell
  grid(m, l, 8, 0, 4, 4, 2);
  MeshCrackResult r = meshCracks(m, l.bounds(16, 8));
  expectConsistent(r);
  EXPECT_EQ(r.cracks, 0);
  EXPECT_EQ(r.unpairedEdges, 0);
  EXPECT_EQ(r.borderEdges, 24);  // the coarse outline: 8 + 8 along z, 4 + 4 along x
  // Of each block's 8 triangles 2 stay: 6 zero-area ones with bit-equal vertices.
  EXPECT_EQ(r.degenerateTriangles, 16 * 6);
  EXPECT_EQ(r.collapsedTriangles, 16 * 6);
}

TEST(MeshCracks, PartialMorphTowardCoarseNeighbourIsClosed) {
  Lattice l;
  Mesh m;
  grid(m, l, 0, 0, 8, 8, 1, partialMorph);
  grid(m, l, 8, 0, 4, 4, 2);
  MeshCrackResult r = meshCracks(m, l.bounds(16, 8));
  expectConsistent(r);
  EXPECT_EQ(r.cracks, 0);
  EXPECT_EQ(r.unpairedEdges, 0);
  EXPECT_EQ(r.borderEdges, 24 + 12);
  // Cells (7, 2m): their first triangle has two vertices at lattice (8, 2m).
  EXPECT_EQ(r.collapsedTriangles, 4);
  EXPECT_EQ(r.degenerateTriangles, 4);

  // The same with the boundary column at k = 1/2 too: its odd vertices sit mid-way on the coarse
  // edges, a T-junction on every one of them.
  Mesh bad;
  grid(bad, l, 0, 0, 8, 8, 1, [](int i, int j) {
    return std::pair<double, double>{i - 0.5 * (i & 1), j - 0.5 * (j & 1)};
  });
  grid(bad, l, 8, 0, 4, 4, 2);
  MeshCrackResult t = meshCracks(bad, l.bounds(16, 8));
  expectConsistent(t);
  EXPECT_EQ(t.crackSites, 4);
  EXPECT_EQ(t.cracks, 12);
}

TEST(MeshCracks, MissingPatchIsOpenButNoCrack) {
  // A hole is what a culled neighbour looks like: its rim is open, nobody overlaps it.
  Lattice l;
  Mesh m;
  grid(m, l, 0, 0, 16, 16, 1);
  for (int j = 5; j < 7; ++j)
    for (int i = 5; i < 7; ++i) removeCell(m, l, i, j);
  ASSERT_EQ(m.size(), size_t(3 * (512 - 8)));
  MeshCrackResult r = meshCracks(m, l.bounds(16, 16));
  expectConsistent(r);
  EXPECT_EQ(r.unpairedEdges, 8);
  EXPECT_EQ(r.cracks, 0);
  EXPECT_EQ(r.crackSites, 0);
  EXPECT_EQ(r.borderEdges, 64);
}

TEST(MeshCracks, TriangleOrderAndWindingDoNotMatter) {
  Lattice l;
  Mesh m;
  grid(m, l, 0, 0, 8, 8, 1);             // fine, z in [0, 8]
  grid(m, l, 8, 0, 4, 4, 2);             // coarse beside it: T-junctions along x = 8
  grid(m, l, 0, 8, 8, 8, 1, fullMorph);  // collapsed above the fine patch: T-junctions along z = 8
  grid(m, l, 8, 8, 4, 4, 2);
  m[3 * (2 * (4 * 8 + 4)) + 2].y -= 0.5f;  // a height gap at lattice (5, 5)
  removeCell(m, l, 2, 2);                  // a hole
  const MeshCrackBounds b = l.bounds(16, 16);
  const MeshCrackResult ref = meshCracks(m, b);
  expectConsistent(ref);
  EXPECT_EQ(ref.cracks, 12 + 12 + 4);
  EXPECT_EQ(ref.crackSites, 4 + 4 + 2);
  EXPECT_EQ(ref.unpairedEdges, 4);
  EXPECT_EQ(ref.borderEdges, (8 + 8) + (4 + 4) + (4 + 4) + (4 + 4));  // per quarter: fine, coarse, collapsed, coarse
  EXPECT_EQ(ref.collapsedTriangles, 16 * 6);
  std::mt19937 rng(20240611);
  for (int round = 0; round < 5; ++round) {
    std::vector<size_t> order(m.size() / 3);
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::shuffle(order.begin(), order.end(), rng);
    Mesh p;
    p.reserve(m.size());
    for (size_t t : order) {
      glm::vec3 v[3] = {m[3 * t], m[3 * t + 1], m[3 * t + 2]};
      std::rotate(v, v + rng() % 3, v + 3);
      if (rng() & 1) std::swap(v[1], v[2]);
      tri(p, v[0], v[1], v[2]);
    }
    expectSame(meshCracks(p, b), ref);
  }
}

TEST(MeshCracks, ParityExactWhenEdgesArriveFarApart) {
  // 540k edge uses in random order: most pairs are far apart in the stream, so the pairing cannot
  // rely on locality.
  Lattice l;
  l.cell = 1000.0f / 300.0f;
  Mesh m;
  grid(m, l, 0, 0, 300, 300, 1);
  m[3 * (2 * (100 * 300 + 200)) + 2].y += 0.25f;  // height gap at lattice (201, 101)
  removeCell(m, l, 17, 250);
  const MeshCrackBounds b = l.bounds(300, 300);
  const MeshCrackResult ref = meshCracks(m, b);
  EXPECT_EQ(ref.borderEdges, 1200);
  EXPECT_EQ(ref.cracks, 4);
  EXPECT_EQ(ref.crackSites, 2);
  EXPECT_EQ(ref.unpairedEdges, 4);
  std::vector<size_t> order(m.size() / 3);
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::shuffle(order.begin(), order.end(), std::mt19937(7));
  Mesh p;
  p.reserve(m.size());
  for (size_t t : order) tri(p, m[3 * t], m[3 * t + 1], m[3 * t + 2]);
  expectSame(meshCracks(p, b), ref);
}

TEST(MeshCracks, NegativeZeroPairsWithPositiveZero) {
  // Lattice origin at 0: x = 0 may come out as -0 from another expression; it is the same vertex.
  Lattice l;
  l.originX = 0.0f;
  Mesh m;
  grid(m, l, 0, 0, 4, 4, 1);
  for (glm::vec3& v : m)
    if (v.x == 0.0f && (&v - m.data()) % 2) v.x = -0.0f;
  MeshCrackResult r = meshCracks(m, l.bounds(4, 4));
  EXPECT_EQ(r.openEdges, 16);
  EXPECT_EQ(r.borderEdges, 16);
}

TEST(MeshCracks, StridedBufferInvalidTrianglesAndBadInput) {
  Lattice l;
  Mesh m;
  grid(m, l, 0, 0, 8, 8, 1);
  std::vector<float> std430(m.size() * 4, 0.0f);
  for (size_t i = 0; i < m.size(); ++i)
    for (int c = 0; c < 3; ++c) std430[4 * i + size_t(c)] = m[i][c];
  expectSame(meshCracks(std430.data(), m.size(), 4, l.bounds(8, 8)), meshCracks(m, l.bounds(8, 8)));

  Mesh withNan = m;
  tri(withNan, l.at(1, 1), glm::vec3(NAN), l.at(2, 2));
  MeshCrackResult r = meshCracks(withNan, l.bounds(8, 8));
  EXPECT_EQ(r.triangles, 129);
  EXPECT_EQ(r.invalidTriangles, 1);
  EXPECT_EQ(r.openEdges, 32);
  EXPECT_EQ(r.cracks, 0);

  EXPECT_EQ(meshCracks(Mesh{}, l.bounds(8, 8)).openEdges, 0);
  EXPECT_THROW(meshCracks(Mesh(4), l.bounds(8, 8)), std::invalid_argument);
  EXPECT_THROW(meshCracks(m, MeshCrackBounds{{1.0f, 0.0f}, {1.0f, 5.0f}}), std::invalid_argument);
  EXPECT_THROW(meshCracks(m, MeshCrackBounds{{0.0f, 0.0f}, {INFINITY, 5.0f}}), std::invalid_argument);
}

TEST(MeshCracks, MillionTrianglesTimed) {
  Lattice l;
  l.cell = 1000.0f / 707.0f;
  Mesh m;
  m.reserve(size_t(3) * 2 * 707 * 708);
  grid(m, l, 0, 0, 707, 708, 1);
  // A T-junction seam and a hole, so that the open-edge phase has work too.
  Mesh coarse;
  grid(coarse, l, 707, 0, 50, 354, 2);
  m.insert(m.end(), coarse.begin(), coarse.end());
  removeCell(m, l, 300, 300);
  const auto t0 = std::chrono::steady_clock::now();
  MeshCrackResult r = meshCracks(m, l.bounds(807, 708));
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("meshCracks: %ld triangles in %.3f s (%ld open, %ld cracks)\n", r.triangles, s, r.openEdges, r.cracks);
  expectConsistent(r);
  EXPECT_EQ(r.cracks, 354 * 3);
  EXPECT_EQ(r.crackSites, 354);
  EXPECT_EQ(r.unpairedEdges, 4);
}
