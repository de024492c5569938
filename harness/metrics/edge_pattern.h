#pragma once
// Shared edges of a quad patch layout with non-uniform patch sizes (Scheme::patchGeometry, e.g.
// sphere-rings) and the vertex patterns fractional_even tessellation puts on an edge, to decide
// whether a large edge and the two half-size edges against it meet vertex for vertex.
#include <cstddef>
#include <tuple>
#include <vector>

#include "render/scheme.h"

namespace lb {

// Axis-aligned footprint of Quad4 patch p (corners c0 and c2, world x and z).
struct PatchRect {
  float x0, z0, x1, z1;
};
PatchRect patchRect(const PatchGeometry& g, size_t patch);

// Side s of a patch in outer-level order (0: -x, 1: -z, 2: +x, 3: +z) as (axis the edge runs along,
// fixed coordinate, lower end, upper end). Corners must sit on an exact lattice (floats compare).
using EdgeKey = std::tuple<int, float, float, float>;
EdgeKey patchSide(const PatchRect& r, int side);

struct PatchSide {
  size_t patch;
  int side;  // outer-level index
};
// A patch side that meets two half-size patch sides (a T-junction boundary between rings).
struct HalfBoundary {
  PatchSide large, lo, hi;  // lo covers the lower half of the large edge, hi the upper half
};
struct QuadEdges {
  std::vector<std::pair<PatchSide, PatchSide>> equal;  // one entry per side shared by two patches
  std::vector<HalfBoundary> half;
};
// Every shared edge of a Quad4 layout whose patches are axis-aligned squares on a lattice.
// Throws std::logic_error if a side is claimed by more than two patches (not a valid layout).
QuadEdges quadPatchEdges(const PatchGeometry& g);

// Vertex parameters in [0, 1] that fractional_even spacing puts on an edge of level `level`.
std::vector<double> fractionalEvenVertices(double level);
// True when the vertices of a large edge (level `large`) on its half `half` (0: [0, 1/2], 1:
// [1/2, 1]) are exactly those of the half-size edge of level `small` lying against that half.
bool fractionalEvenHalfMatches(double large, double small, int half);
// Both halves: the large edge's vertices are exactly the union of its two neighbours'.
bool fractionalEvenPatternsMatch(double large, double smallLo, double smallHi);

}  // namespace lb
