#pragma once
// Load-time part of cdlod-sse (schemes/cdlod_sse.cpp): every quadtree node's geometric error, the
// largest vertical distance between its triangulated grid and the bilinear heightfield.
#include <memory>
#include <vector>

#include "schemes/preprocess/min_max_pyramid.h"

namespace lb {

struct Heightfield;

// Per pyramid level (= node level, base = node cells n), the largest deviation of the node's cells
// of 2^l lattice cells, each split along its (0,0)-(1,1) diagonal as cdlod's footprint is,
// vertices clamped to the border as its shader clamps them (schemes/preprocess/tess_deviation.h's
// exact triangle scan).
struct NodeErrors {
  std::vector<std::vector<float>> dev;  // dev[p][pyr.index(p, i, j)], world units, >= 0
};

NodeErrors computeNodeErrors(const Heightfield& hf, const MinMaxPyramid& pyr, double q);

// The same, kept for the last few (heights, node size, lattice): the scan costs seconds on large
// terrains and matched searches set the scheme once per candidate value. Safe on any thread; the
// table is shared, never changed.
std::shared_ptr<const NodeErrors> cachedNodeErrors(const Heightfield& hf, const MinMaxPyramid& pyr, double q);

}  // namespace lb
