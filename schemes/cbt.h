#pragma once
// The tree cbt and cbt-ts share (schemes/cbt.cpp says its rules): their parameters, the leaf mesh,
// the state and the passes. `perDraw` > 0 splits the leaves into draws of at most that many
// instances (GpuLod::maxDraws); 0 draws them all at once.
#include <cstdint>
#include <vector>

#include "render/scheme.h"

namespace lb {

GpuLod cbtTree(const Heightfield& hf, const ParamValues& v, uint32_t perDraw);
// cbt's parameters, which cbt-ts takes as they are.
const std::vector<ParamSpec>& cbtParams();
// Micro-triangles at rest project to t^2/16 ... t^2/8 px: the middle of that octave, t^2 / (8 sqrt 2).
double cbtTargetAreaPx(const ParamValues& v);

}  // namespace lb
