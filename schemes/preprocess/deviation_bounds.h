#pragma once
// Cheap upper bounds on the deviations tessDeviation() computes exactly (schemes/preprocess/tess_deviation.h),
// so that the table can skip every edge and triangle whose bound cannot beat its level's running
// maximum: the maximum is exact, so the table is the same bits as computing everything.
//
// The heightfield is cut into blocks of n x n cells (n = f, 4f, 16f: an item uses the finest size
// that covers it with a few blocks, so a bound costs a few blocks; f, 1 to 4, follows the patch
// size so that the finest blocks are no larger than the finest level's cells). Each block keeps
// a plane Q (through the block's first sample, with the slope of its corners) and the range [lo, hi] of
// h - Q over its samples. The bilinear surface reproduces planes, so B - Q over the whole block is
// the bilinear interpolation of those residuals and stays in [lo, hi]. For any plane P (a
// triangle's, or one through an edge's chord), B - P = (B - Q) + (Q - P) on the block, and Q - P
// is linear, largest at a block corner: a few multiplications per block bound |B - P| there.
#include <glm/vec2.hpp>
#include <vector>

namespace lb {

struct Heightfield;

class DeviationBounds {
 public:
  // Blocks covering texel x in [x0, x1], z in [z0, z1] (one patch), clamped to the heightfield;
  // the finest blocks have fine (1, 2 or 4) cells a side.
  void build(const Heightfield& hf, double x0, double z0, double x1, double z1, int fine);
  // The finest block size for patches of sx x sz texels: their level-64 cells, at most 4.
  static int fineFor(double sx, double sz);

  // >= the value edgeDeviation / interiorDeviation compute (in floating point) for the segment
  // a->b with chord heights ha, hb, or for the samples inside triangle abc under the plane
  // through ha, hb, hc: a relative slack covers the rounding of both computations.
  double edge(glm::dvec2 a, glm::dvec2 b, double ha, double hb) const;
  // A tighter bound for a long edge (the finest blocks along it only), at more cost.
  double edgeAlong(glm::dvec2 a, glm::dvec2 b, double ha, double hb) const;
  double triangle(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c, double ha, double hb, double hc) const;

 private:
  struct Block {
    double x, z;    // first sample (the plane's origin)
    double wx, wz;  // extent in texels (the level's size, less at the last row / column)
    double qx, qz;  // the plane's slope
    double lo, hi;  // range of h - plane over the block's samples
  };
  // max |B - P| over the blocks of levels_[level] meeting z in [zlo, zhi] and, in each row of
  // blocks, x in the range span(z0, z1, xlo, xhi) gives for the row's part [z0, z1]. P is the
  // plane of slope (gx, gz) through height h0 at p; with kChord, P's slope is each block's own
  // plus a multiple of d, so that P has slope dh along d (an edge's chord) and follows the block
  // across it.
  template <bool kChord, class Span>
  double overBlocks(int level, double zlo, double zhi, Span&& span, glm::dvec2 p, double h0, double gx, double gz,
                    glm::dvec2 d, double dh) const;
  int levelFor(double extent) const;

  struct Level {
    int size = 0;                          // cells per block side
    int bx0 = 0, bz0 = 0, nx = 0, nz = 0;  // global index of the first block built, blocks built per side
    int blocksX = 0, blocksZ = 0;          // blocks of the whole heightfield per side
    std::vector<Block> blocks;
  };
  static constexpr int kLevels = 3;
  Level levels_[kLevels];
  double maxAbs_ = 0;  // largest |h| of the blocks (scale of the slack)
  bool finite_ = true;
};

}  // namespace lb
