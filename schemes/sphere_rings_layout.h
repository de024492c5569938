#pragma once
// sphere-rings' layout rules (schemes/sphere_rings.cpp), shared with its tests.
#include <glm/glm.hpp>

#include "render/scheme.h"

namespace lb {

// Scheme buffer: kRingHeaderFloats header floats ([r] = offset of ring level r's bounds,
// [kRingMaxLevels] = offset of the patch records, both in vec2 units), then kRingFloatsPerPatch
// floats per patch (adjacency -x, -z, +x, +z; patch x, z in its tile; ring; 0), then per ring
// level r a ringLatticeSize^2 row-major array of (minHeight, maxHeight) over the world lattice
// cells of size 2^r x extent / grid.
constexpr int kRingMaxLevels = 8;
constexpr int kRingHeaderFloats = 10;
constexpr int kRingFloatsPerPatch = 8;

// Number of rings for these parameters at this grid; throws InputError when an explicit `rings`
// leaves part of the terrain uncovered from some camera position.
int ringCount(const ParamValues& values, int grid);
// The rings' centre in lattice units (extent / grid): the eye snapped to a multiple of the
// coarsest patch size 2^(rings-1) and clamped to [0, grid].
glm::ivec2 ringCentre(glm::dvec2 eyeXZ, double extent, int grid, int rings);
// World lattice cells per side at ring level r: ceil(grid / 2^r).
long ringLatticeSize(int grid, int ring);

}  // namespace lb
