#pragma once
// Load-time part of cdlod and cdlod-sse (schemes/cdlod.h): the min-max pyramid of the lattice, the
// height range of every square block of lattice cells at every power-of-two size, from which the
// schemes' quadtree nodes take their boxes.
#include <glm/glm.hpp>
#include <vector>

namespace lb {

struct Heightfield;

// Pyramid level p holds blocks of base * 2^p lattice cells a side; a node of n cells at level l is
// block (p = l + log2(n / base)). Levels below `built` have their sizes but no bounds yet: a
// scheme that may draw several node sizes builds the fine levels only when a frame draws the small
// ones (at 65537^2 blocks of 4 cells are 2.9 GB, which a 1080p frame never reads).
struct MinMaxPyramid {
  double cellsX = 0, cellsZ = 0;  // lattice extent in finest cells: (samples - 1) * cells_per_texel
  glm::dvec2 cell{0};             // finest cell in world units
  double q = 1;                   // cells per sample spacing
  int base = 4;
  int built = 0;  // the finest level with bounds
  std::vector<int> nx, nz;
  std::vector<std::vector<glm::vec2>> bounds;  // (min, max) height per block; empty below `built`
  int top() const { return int(nx.size()) - 1; }
  // base * 2^p as a product: exact for every level the pyramid has (p >= -1), and ldexp's library
  // call was a tenth of the per-frame selection.
  double size(int p) const { return p >= 0 ? double(base) * double(1u << p) : double(base) * 0.5; }
  size_t index(int p, int i, int j) const { return size_t(j) * size_t(nx[size_t(p)]) + size_t(i); }
};

// Contract: q (cells per sample spacing) a power of two, `cell` the finest cell in world units
// (render/instanced.h latticeCell). Levels go up until one block of at least minTopCells holds the
// lattice. Each block's range is that of every sample the bilinear surface over it touches. Bounds
// are made from level `firstLevel` up (clamped to the top).
MinMaxPyramid buildMinMaxPyramid(const Heightfield& hf, double q, int base, int minTopCells, glm::dvec2 cell,
                                 int firstLevel = 0);

// Makes the bounds of levels `level` to pyr.built - 1 from hf (the terrain the pyramid was built
// from): the same bits as building them at once, since a block's samples are its children's.
void extendMinMaxPyramid(MinMaxPyramid& pyr, const Heightfield& hf, int level);

}  // namespace lb
