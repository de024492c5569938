#pragma once
// The tree cbt and cbt-ts share (schemes/cbt.cpp says its rules): their parameters, the leaf mesh,
// the state, the passes and the records' capacity (the pool rule, from the terrain, the view budget
// and the device's limits in `budget`). `perDraw` > 0 splits the leaves into draws of at most that
// many instances (GpuLod::maxDraws); 0 draws them all at once.
#include <cstdint>
#include <vector>

#include "render/scheme.h"

namespace lb {

GpuLod cbtTree(const Heightfield& hf, const ParamValues& v, const GpuLodBudget& budget, uint32_t perDraw);
// The pool the rule gives with no `pool` parameter: the view budget's leaves, 4 x viewport px /
// (4^subd t^2 / 16), rounded up to a power of two of at least 2^17 (large_cbt's 128K).
uint64_t cbtViewPool(const GpuLodBudget& budget, const ParamValues& v);
// cbt's parameters, which cbt-ts takes as they are.
const std::vector<ParamSpec>& cbtParams();
// Micro-triangles at rest project to t^2/16 ... t^2/8 px: the middle of that octave, t^2 / (8 sqrt 2).
double cbtTargetAreaPx(const ParamValues& v);

}  // namespace lb
