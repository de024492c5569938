#pragma once
// Load-time part of `chunked` (schemes/chunked.cpp): Ulrich's quadtree of chunks, each chunk's
// mesh simplified offline to its level's geometric error and sealed with a skirt.
//
// Lattice: one cell per heightfield sample spacing, terrain-local integer coordinates (as the
// instanced path's footprints, render/instanced.h). A level-l chunk covers leafCells * 2^l cells a
// side (clipped at the terrain's last sample); the root covers the whole terrain.
//
// Simplifier (written here, for heightfields): a restricted quadtree of square cells inside the
// chunk, a cell split while the largest vertical distance between its two triangles (diagonal
// (0,0)-(1,1)) and the bilinear heightfield exceeds the level's target error e_l = e_0 * 2^l, down to
// single cells; a leaf cell with corners of smaller neighbours on its sides is fanned from its
// centre, so the chunk's mesh is conforming inside. Vertices stay on heightfield samples.
// Recorded error of a chunk: the exact largest distance of its drawn triangles from the bilinear
// heightfield (schemes/preprocess/tess_deviation.h), raised to its children's, so errors never
// decrease up the tree (the selection's refinement then stops at a monotone cut).
//
// Skirt: below every chunk side that is not on the terrain border, a vertical wall from the side's
// surface polyline down to a bottom line shared by every chunk: bottom points at the multiples of
// leafCells along the side (and at the terrain's last sample), each at its sample's height minus
// one terrain-wide depth D. D is the least that keeps every bottom under every chunk's surface along
// every side (computed exactly: both are piecewise linear between lattice points), so skirts hang
// below the surface and never show above it. Two chunks sharing a side, at any levels, then draw the
// same bottom segments: their walls together span the gap between their surfaces, and the drawn mesh
// is closed (every edge used twice), which metrics/mesh_cracks.h checks exactly.
#include <cstdint>
#include <glm/vec2.hpp>
#include <memory>
#include <vector>

namespace lb {

struct Heightfield;

// A skirt's bottom vertex is stored with x = -(x + 1): lattice coordinates are otherwise >= 0.
inline float skirtBottomX(int x) {
  return -float(x) - 1.0f;
}

// A chunk's triangle list in lattice units, as the instanced path's footprints hold it.
struct ChunkMesh {
  std::vector<glm::vec2> vertices;
  std::vector<uint32_t> indices;
};

struct Chunk {
  int level = 0;
  int x0 = 0, z0 = 0, x1 = 0, z1 = 0;  // lattice cells covered
  float hmin = 0, hmax = 0;            // heights of the samples it covers (its surface lies within)
  float target = 0;                    // e_l, world units
  float measured = 0;                  // its surface's exact largest distance from the heightfield
  float error = 0;                     // max(measured, children's error): what the selection projects
  int children[4] = {-1, -1, -1, -1};  // indices into ChunkTree::chunks, -1 = none (leaf or past the border)
  uint32_t surfaceTriangles = 0, skirtTriangles = 0;
  ChunkMesh mesh;  // surface triangles first, then the skirt's
};

struct ChunkTree {
  int leafCells = 0, levels = 0;
  double leafError = 0;  // e_0, world units
  std::vector<Chunk> chunks;
  int root = -1;
  float skirtDepth = 0;  // D, world units
  double buildSeconds = 0;
  uint64_t vertexCount = 0, indexCount = 0;
  uint64_t meshBytes() const { return vertexCount * 8 + indexCount * 4; }  // as the instanced path uploads them
};

// Contract: leafCells a power of two >= 2; leafErrorCells > 0 (e_0 = leafErrorCells x the larger
// sample spacing, so the rule is scale-free); heightfield at least 2 x 2. Chunks of one level are
// built in parallel; the result does not depend on the thread count.
ChunkTree buildChunkTree(const Heightfield& hf, int leafCells, double leafErrorCells);

// The same, kept for the last few (heights, size, extent, settings): matched searches and
// repeated cases set the scheme again on the same terrain. Safe on any thread; never changed.
std::shared_ptr<const ChunkTree> cachedChunkTree(const Heightfield& hf, int leafCells, double leafErrorCells);

}  // namespace lb
