#pragma once
// Analytic cracks of a draw path without tessellation (instanced grid, GPU-indirect, mesh shaders),
// computed from the triangles it drew rather than from tessellation levels. Input: every drawn
// triangle's three world-space vertices exactly as the vertex stage emitted them. Shared vertices of
// neighbouring instances are bit-identical (render/instanced.h: one float expression of integer
// lattice coordinates), so a watertight mesh pairs every interior edge exactly.
//
// Rules:
// 1. Edges whose two endpoints are bit-equal (zero length) are dropped.
// 2. Undirected 3-D edges, keyed by the bit patterns of their endpoints (-0 read as +0), are counted
//    by parity: two uses cancel. Zero-area triangles with two bit-equal vertices (a collapsed morph
//    block, a border clamp) use one edge twice and vanish; a stitching strip of triangles A-M-B along a
//    coarse edge A-B cancels both the fine side's A-M, M-B and the coarse side's A-B.
// 3. Edges left with odd parity are open. Open edges with both endpoints on one side of the terrain
//    border are the mesh's outline and ignored.
// 4. An open interior edge is a crack when another open interior edge overlaps it collinearly in xz
//    with positive length: the coarse edge and the fine edges of a T-junction, or the two copies of an
//    edge whose shared vertex has two heights. Open edges nobody overlaps are "unpaired": the side of a
//    culled or missing neighbour. A culled side is off screen (culling is conservative), so that is no
//    crack, the rule of metrics/cracks.h. Parity cannot see a patch drawn twice (its outline turns
//    open and unpaired) nor a vertex moved off its partner's line in xz (an open sliver, no overlap);
//    lattice schemes make neither: their vertices sit on lattice points or move along lattice lines.
//
// Tolerance. Axis-parallel lattice edges keep bit-equal constant coordinates, but a lattice point
// on a diagonal lattice edge lies on the rounded edge only up to float rounding. Every lattice
// vertex lies within about one ulp of the coordinate magnitude M of the exact affine image of its
// lattice point (one rounded product, one rounded sum; the float cell is a common exact scale), so a
// T-junction vertex is at most ~3 ulps(M) off its partner's line. Collinearity and positive overlap
// use tol = 8 * FLT_EPSILON * M, M = the largest |coordinate| or side of the border rectangle: ~2.5x
// that bound, and still 1/16 of the finest cell of a 16385-sample terrain at 4 cells per texel.
// Border membership uses the same tol, so the rectangle need not reproduce the shader's float
// expression bit for bit.
#include <cstddef>
#include <glm/glm.hpp>
#include <vector>

namespace lb {

// The terrain's world rectangle in x (min.x .. max.x) and z (min.y .. max.y), origin included.
struct MeshCrackBounds {
  glm::vec2 min{0.0f}, max{0.0f};
};

struct MeshCrackResult {
  long triangles = 0;            // triangles read, invalid ones included
  long invalidTriangles = 0;     // a non-finite coordinate: skipped (the GPU draws nothing defined)
  long degenerateTriangles = 0;  // zero xz area up to tol (collapsed ones included)
  long collapsedTriangles = 0;   // two bit-equal vertices (hist_degenerate also counts collinear ones)
  long openEdges = 0;            // odd parity after cancelling: borderEdges + unpairedEdges + cracks
  long borderEdges = 0;          // open, on the terrain border: ignored
  long unpairedEdges = 0;        // open, interior, overlapped by no other open edge (culled or missing neighbour)
  long cracks = 0;               // open interior edges that another open interior edge overlaps collinearly in xz
  long crackSites = 0;           // connected groups of crack edges under "overlaps": one coarse edge with its
                                 // T-junction halves, one edge seen at two heights; the analogue of one
                                 // mismatched shared edge in metrics/cracks.h
  double tolerance = 0.0;        // the tol used, world units
};

// `triangleVertices` holds 3 vertices per drawn triangle (x, y = height, z). Throws
// std::invalid_argument when its size is not a multiple of 3 or the bounds are not a finite
// rectangle of positive size. Single-threaded; about 0.1 s per million triangles on one core when
// most edges pair (2 M: 0.18 s), plus about 0.5 us per open edge (a mesh with every other cell
// missing, 1 M triangles: 0.94 s).
MeshCrackResult meshCracks(const std::vector<glm::vec3>& triangleVertices, const MeshCrackBounds& terrainBorder);

// The same over a raw capture buffer: `vertexCount` vertices (a multiple of 3) of x, y, z floats
// starting every `strideFloats` floats (3 packed, 4 for std430 vec3 arrays).
MeshCrackResult meshCracks(const float* vertices, size_t vertexCount, size_t strideFloats,
                           const MeshCrackBounds& terrainBorder);

}  // namespace lb
