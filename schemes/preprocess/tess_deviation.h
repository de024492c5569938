#pragma once
// Load-time part of the `errbound` scheme (schemes/errbound.cpp): per patch of the uniform base
// grid and per power-of-two tessellation level, the largest vertical distance between the
// surface the tessellator actually draws at that level and the true bilinear heightfield,
// anywhere in the patch (not only at heightfield samples).
#include <glm/vec2.hpp>
#include <vector>

namespace lb {

struct Heightfield;

constexpr int kErrboundLevels = 7;  // levels 1, 2, 4, ..., 64: level index k is 2^k

struct DeviationTable {
  int grid = 0;
  std::vector<float> dev;  // dev[(j * grid + i) * kErrboundLevels + k], world units, >= 0
  float at(int patch, int k) const { return dev[size_t(patch) * kErrboundLevels + size_t(k)]; }
};

// Contract: grid >= 1, heightfield at least 2 x 2. Deterministic; runs on all hardware threads.
// dev(p, k) bounds |tessellated - true height| over patch p whatever its four edge levels are,
// as long as each is a power of two >= 2^k (errbound's edges are the max of two patches' levels).
// Patches of 32 texels or more skip every edge and triangle whose cheap upper bound
// (schemes/preprocess/deviation_bounds.h) cannot raise its level's maximum (tessDeviationBounded); smaller
// ones, where that does not pay, take tessDeviationReference. The same bits either way.
DeviationTable tessDeviation(const Heightfield& hf, int grid);
DeviationTable tessDeviationBounded(const Heightfield& hf, int grid);  // the bounds at any patch size

// The same table computed the straightforward way, every edge and triangle of every level: the
// oracle tessDeviation is tested against, bit for bit.
DeviationTable tessDeviationReference(const Heightfield& hf, int grid);

// Largest |plane through the three vertices - bilinear heightfield| over the triangle, vertices in
// heightfield texel coordinates (x along width, z along height). Exact up to rounding: the
// difference of a bilinear cell and a plane has no interior extremum, so the maximum lies on the
// boundary of a cell-triangle piece: on a triangle edge (a quadratic between grid-line crossings)
// or on a grid line (linear between samples, so at a sample inside the triangle).
// rowsInParallel: the samples inside are scanned in bands of rows on the terrain threads
// (terrain/parallel_rows.h), for a caller with fewer triangles than threads (the top levels of a
// quadtree over a large terrain: one triangle there covers half the terrain). The same bits.
double triangleDeviation(const Heightfield& hf, glm::dvec2 a, glm::dvec2 b, glm::dvec2 c, bool rowsInParallel = false);

// The triangles of one patch at inner level 2^k with the given power-of-two edge levels, in the
// patch's (u, v) domain, as the D3D11 / Vulkan reference tessellator (Mesa lavapipe, and the
// pattern hardware follows) emits them for integer partitioning; interior cells are listed with
// both diagonals (4 triangles), so a device that picks other diagonals is still covered.
// edges: levels of u=0, v=0, u=1, v=1 (Vulkan outer order). 3 points per triangle.
std::vector<glm::dvec2> patchTriangles(int k, const int edges[4]);

}  // namespace lb
