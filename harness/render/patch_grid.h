#pragma once
// The base grid: (N+1)^2 vertices over the terrain and the control-point indices of each patch.
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "render/scheme.h"

namespace lb {

struct Heightfield;

std::vector<glm::vec2> gridVertices(int n, float extent);
// Quad4: corners (i,j) (i+1,j) (i+1,j+1) (i,j+1). Quad12: the corners, then two points of each
// neighbour across edges u=0, v=0, u=1, v=1 (clamped at the border, ch9 Listing 9.2).
// Tri3: two triangles per quad, (00, 10, 11) and (00, 11, 01); patch = 2 * quad + k.
std::vector<uint32_t> patchIndices(int n, Topology topology);
uint32_t controlPointCount(Topology topology);
uint32_t patchCountFor(int n, Topology topology);
// The patches a scheme draws on a base grid of n x n: its own patch geometry, else the uniform grid
// of its topology with the height bounds, moved into the world by the terrain's origin (unless in
// the scheme's own units). The tessellation path draws them; a mesh path that decides its LOD per
// patch (render/mesh_drawer.cpp) reads the same corners and bounds.
PatchGeometry drawnPatches(const Scheme& scheme, const ParamValues& params, const Heightfield& hf, int n);
// Per patch (minHeight, maxHeight) over every heightfield sample the patch's bilinear surface touches.
std::vector<glm::vec2> patchHeightBounds(const Heightfield& hf, int n, Topology topology);
// (minHeight, maxHeight) over every sample the bilinear surface over the world rectangle [lo, hi] touches;
// parts outside the terrain see the clamped border, as terrainHeight() does.
glm::vec2 rectHeightBounds(const Heightfield& hf, glm::vec2 lo, glm::vec2 hi);

}  // namespace lb
