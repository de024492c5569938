#pragma once
// Triangle patterns of one quad patch for a mesh-shader draw path: the triangles the fixed-function
// tessellator would make of the patch, made ahead of time in pieces small enough for one mesh
// workgroup each. Design and the mesh shader's side: docs/draw-paths.md, "Tessellation patterns
// for mesh shaders".
//
// Domain. As shaders/terrain_quad.tese: u along the patch's x, v along its z; outer factors in
// gl_TessLevelOuter order (edges u=0, v=0, u=1, v=1), inner factors along u and along v.
//
// Rules, and why:
// - Equal spacing on integer factors: vertex i of an edge of factor n is at i/n, stored as that
//   fraction. The tessellator places the same points under `equal_spacing` (the sphere scheme with
//   integer=1) and under `fractional_even` at even factors, so a mesh path fed the same factors
//   draws the same edges. Neighbours agree on an edge's factor and nothing else, so the edge's
//   points depend on n alone; and a fraction becomes the same float on both sides (one correctly
//   rounded division), so shared edges are bit-identical. A mirrored edge must use (n - i) / n,
//   never 1 - i/n.
// - The interior is the grid (a/m0, b/m1), 0 < a < m0, 0 < b < m1, and an inner factor of 1 counts
//   as 2 unless all six factors are 1: the tessellator does the same ("1 + epsilon"), so a pattern
//   has its vertex set and therefore its counts, V = sum(outer) + (m0-1)(m1-1) vertices and
//   T = sum(outer) + 2(m0-1)(m1-1) - 2 triangles (a triangulated disc with B border and I inner
//   vertices has B + 2I - 2 triangles, whatever its connectivity). It also leaves every edge an
//   interior point to stitch to, so no triangle lies on an edge.
// - Connectivity: the grid cells inside the first ring, two triangles each, and four strips, each
//   stitching an edge's segments to the first ring's side by merging the two rows' segment
//   midpoints. Strips between parallel rows cannot fold, whatever the factors.
// - Counter-clockwise in (u, v) (positive (b - a) x (c - a)), like the instanced footprints and
//   the tessellated grids: every triangle faces up, so back-face counts mean the same on every path.
// - Cap: a piece spans at most kTessCap segments of any edge and kTessCap grid columns and rows.
//   A piece is then a disc with at most 4C border and (C-1)^2 inner vertices: at C = 11 at most 144
//   vertices and 242 triangles, within the 256 and 256 that VK_EXT_mesh_shader guarantees on every
//   device (the H100 offers exactly that); C = 12 would allow 288 triangles.
// - Above the cap the patch is split into k0 x k1 sub-patches, k0 = max(ceil(m0/C), ceil(n1/C),
//   ceil(n3/C)) columns, k1 likewise from m1, n0 and n2: column x takes grid lines x*m0/k0 ..
//   (x+1)*m0/k0 and segments x*n/k0 .. (x+1)*n/k0 of each edge it touches (integer division), so
//   pieces differ by at most one segment. One level of ceil(f/C) is the fewest workgroups; halving
//   recursively would give 4 pieces of factor 12 where 2 do. The split only partitions triangles:
//   sub-patches share grid points and the strips' cut edges (rungs), whose points are the parent's
//   own fractions, so they meet without cracks, the patch edges still carry exactly i/n, and the
//   counts are those of the whole pattern. Only strips change: they are cut at the rungs.
#include <array>
#include <cstdint>
#include <vector>

namespace lb {

constexpr int kTessCap = 11;
constexpr int kTessMaxFactor = 64;  // maxTessellationGenerationLevel the renderer requires
// VK_EXT_mesh_shader's required minimums of maxMeshOutputVertices and maxMeshOutputPrimitives.
constexpr int kMeshMinOutputVertices = 256;
constexpr int kMeshMinOutputPrimitives = 256;

struct TessFactors {
  std::array<int, 4> outer{};  // edges u=0, v=0, u=1, v=1; 0 culls the patch
  std::array<int, 2> inner{};  // along u, along v
};

struct TessFraction {
  uint16_t num = 0, den = 1;
  float value() const { return float(num) / float(den); }
};

struct TessVertex {
  TessFraction u, v;
};

// What one mesh workgroup emits: its vertices and counter-clockwise triangles (local indices).
struct TessSubPatch {
  int column = 0, row = 0;
  std::vector<TessVertex> vertices;
  std::vector<std::array<uint8_t, 3>> triangles;
};

struct TessPattern {
  TessFactors factors;                   // as tessellated: inner factors rounded as the tessellator rounds them
  int columns = 0, rows = 0;             // the split; 1 x 1 within the cap, 0 x 0 when culled
  std::vector<TessSubPatch> subPatches;  // row-major, sub-patches without triangles left out
};

// The whole patch as one welded mesh: every vertex once, three indices a triangle.
struct TessMesh {
  std::vector<TessVertex> vertices;
  std::vector<uint32_t> indices;
};

// What the tessellator makes of a float level under equal_spacing: 0 for <= 0 or NaN (an outer
// level there culls the patch), else the level clamped to [1, kTessMaxFactor] and rounded up.
int equalSpacingFactor(float level);

// Contract (asserted): factors in [0, kTessMaxFactor], 2 <= cap <= kTessCap. An inner factor of 0
// counts as 1. Deterministic: the same factors give the same sub-patches, vertices and order.
TessPattern tessellateQuad(const TessFactors& factors, int cap = kTessCap);
TessMesh weldPattern(const TessPattern& pattern);

// A strip of p edge segments stitched to q first-ring segments, walked in the patch's
// counter-clockwise direction: bit t set when triangle t advances along the edge. 0 <= p, q <= cap.
uint32_t stripSteps(int p, int q);
// The table a mesh shader reads instead of walking the merge (each thread then finds its
// triangle's two rows with one bitCount): entry p * (cap + 1) + q, 4 (cap + 1)^2 bytes, 576 at the
// cap. Grid cells and vertex positions are arithmetic, so this is all a pattern needs uploaded.
std::vector<uint32_t> stripTable(int cap = kTessCap);

}  // namespace lb
